#!/usr/bin/env python3
"""Checks that the workspace's `rust-version` is what the code really needs: the newest
`rust-version` any dependency in Cargo.lock's resolved graph declares (the code itself uses
nothing newer; no other toolchain can be installed here to try an older one).

Usage: python3 scripts/rust_version.py   (exit 1, naming the package, on a mismatch)
"""
import json
import subprocess
import sys


def version(v):
    return tuple(int(x) for x in v.split("."))[:2]


meta = json.loads(
    subprocess.run(
        ["cargo", "metadata", "--format-version", "1", "--locked", "--all-features"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
)
resolved = {n["id"] for n in meta["resolve"]["nodes"]}
members = set(meta["workspace_members"])
deps = [p for p in meta["packages"] if p["id"] in resolved and p["id"] not in members]
declared = {p.get("rust_version") for p in meta["packages"] if p["id"] in members}
if len(declared) != 1 or None in declared:
    sys.exit(f"every workspace crate should take the workspace's rust-version, got {declared}")
ours = version(declared.pop())
need, who = max(
    ((version(p["rust_version"]), p["name"] + " " + p["version"]) for p in deps if p.get("rust_version")),
    default=((0, 0), "nothing"),
)
if need != ours:
    sys.exit(
        f"rust-version is {ours[0]}.{ours[1]} but the dependencies need {need[0]}.{need[1]} ({who}): "
        "set [workspace.package] rust-version to that"
    )
print(f"rust-version {ours[0]}.{ours[1]}: what the newest dependency needs ({who})")
