//! Rigs cross processes (Dask workers, multiprocessing) by pickling: a `chasles_skin::Rig`
//! written as one byte string — every public field, little-endian, versioned — and read
//! back through `Rig::new`, which checks it as every loader's rig is checked. Reading never
//! panics and never allocates more than the bytes can hold: each count is checked against
//! what is left before anything is made of it. (Poses pickle as their arrays; see
//! [`crate::skin`].)

use chasles::{Mat4, Quat, Vec3};
use chasles_skin::animation::{Animation, Channel, Interpolation, Path};
use chasles_skin::{Influences, Mesh, Node, Rig, Trs};

/// The first bytes of a pickled rig: the format and its version.
const MAGIC: &[u8; 8] = b"CHRIG\x001\x00";

/// Appends numbers and strings little-endian.
struct Writer(Vec<u8>);

impl Writer {
    fn u64(&mut self, v: usize) {
        self.0.extend_from_slice(&(v as u64).to_le_bytes());
    }
    fn f32s(&mut self, v: &[f32]) {
        self.u64(v.len());
        for x in v {
            self.0.extend_from_slice(&x.to_le_bytes());
        }
    }
    fn str(&mut self, s: &str) {
        self.u64(s.len());
        self.0.extend_from_slice(s.as_bytes());
    }
    fn trs(&mut self, t: &Trs) {
        let r = t.rotation;
        let mut v = t.translation.to_array().to_vec();
        v.extend([r.w, r.x, r.y, r.z]);
        v.extend(t.scale.to_array());
        self.f32s(&v);
    }
}

/// The bytes of a rig.
pub fn rig_to_bytes(rig: &Rig) -> Vec<u8> {
    let mut w = Writer(MAGIC.to_vec());
    w.str(&rig.name);
    let flat = |v: &[Vec3<f32>]| v.iter().flat_map(|p| p.to_array()).collect::<Vec<f32>>();
    w.f32s(&flat(&rig.mesh.positions));
    w.f32s(&flat(&rig.mesh.normals));
    w.u64(rig.mesh.triangles.len());
    for t in rig.mesh.triangles.iter().flatten() {
        w.0.extend_from_slice(&t.to_le_bytes());
    }
    w.u64(rig.nodes.len());
    for n in &rig.nodes {
        w.str(&n.name);
        w.u64(n.parent.map_or(0, |p| p + 1));
        w.trs(&n.rest);
    }
    w.u64(rig.joints.len());
    for j in &rig.joints {
        w.u64(*j);
    }
    let ib: Vec<f32> = rig
        .inverse_bind
        .iter()
        .flat_map(|m| m.to_row_major())
        .collect();
    w.f32s(&ib);
    let inf = &rig.influences;
    w.u64(inf.start.len());
    for s in &inf.start {
        w.0.extend_from_slice(&s.to_le_bytes());
    }
    w.u64(inf.joints.len());
    for j in &inf.joints {
        w.0.extend_from_slice(&j.to_le_bytes());
    }
    w.f32s(&inf.weights);
    w.u64(rig.animations.len());
    for a in &rig.animations {
        w.str(&a.name);
        w.u64(a.channels.len());
        for c in &a.channels {
            w.u64(c.node);
            w.u64(match c.path {
                Path::Translation => 0,
                Path::Rotation => 1,
                Path::Scale => 2,
            });
            w.u64(match c.interpolation {
                Interpolation::Linear => 0,
                Interpolation::Step => 1,
                Interpolation::CubicSpline => 2,
            });
            w.f32s(&c.times);
            let v: Vec<f32> = c.values.iter().flatten().copied().collect();
            w.f32s(&v);
        }
    }
    w.0
}

/// Reads what [`Writer`] wrote, checking every count against the bytes left.
struct Reader<'a>(&'a [u8]);

type R<T> = Result<T, String>;

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> R<&'a [u8]> {
        if n > self.0.len() {
            return Err("the pickled rig is truncated".into());
        }
        let (a, b) = self.0.split_at(n);
        self.0 = b;
        Ok(a)
    }
    fn u64(&mut self) -> R<usize> {
        let b: [u8; 8] = self.take(8)?.try_into().map_err(|_| "truncated")?;
        usize::try_from(u64::from_le_bytes(b)).map_err(|_| "a count past usize".into())
    }
    /// A count of items of `size` bytes each, no more than the bytes left can hold.
    fn count(&mut self, size: usize) -> R<usize> {
        let n = self.u64()?;
        if n.checked_mul(size).is_none_or(|b| b > self.0.len()) {
            return Err("the pickled rig is truncated".into());
        }
        Ok(n)
    }
    fn f32s(&mut self) -> R<Vec<f32>> {
        let n = self.count(4)?;
        Ok(self
            .take(n * 4)?
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect())
    }
    fn str(&mut self) -> R<String> {
        let n = self.count(1)?;
        String::from_utf8(self.take(n)?.to_vec()).map_err(|_| "a name is not UTF-8".into())
    }
    fn vec3s(&mut self) -> R<Vec<Vec3<f32>>> {
        let v = self.f32s()?;
        if v.len() % 3 != 0 {
            return Err("a vector list is not whole".into());
        }
        Ok(v.chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect())
    }
    fn trs(&mut self) -> R<Trs> {
        let v = self.f32s()?;
        let [tx, ty, tz, w, x, y, z, sx, sy, sz]: [f32; 10] = v
            .try_into()
            .map_err(|_| "a node transform is not 10 numbers")?;
        Ok(Trs {
            translation: Vec3::new(tx, ty, tz),
            rotation: Quat::new(w, x, y, z),
            scale: Vec3::new(sx, sy, sz),
        })
    }
}

/// A rig from [`rig_to_bytes`]'s bytes, checked by `Rig::new`.
pub fn rig_from_bytes(bytes: &[u8]) -> R<Rig> {
    let mut r = Reader(bytes);
    if r.take(MAGIC.len()).ok() != Some(MAGIC.as_slice()) {
        return Err("not a pickled chasles rig (or one of another version)".into());
    }
    let name = r.str()?;
    let positions = r.vec3s()?;
    let normals = r.vec3s()?;
    let nt = r.count(12)?;
    let triangles = r
        .take(nt * 12)?
        .chunks_exact(12)
        .map(|c| {
            let u = |k: usize| u32::from_le_bytes([c[k], c[k + 1], c[k + 2], c[k + 3]]);
            [u(0), u(4), u(8)]
        })
        .collect();
    let nn = r.count(16)?;
    let mut nodes = Vec::with_capacity(nn);
    for _ in 0..nn {
        let name = r.str()?;
        let parent = r.u64()?.checked_sub(1);
        nodes.push(Node {
            name,
            parent,
            rest: r.trs()?,
        });
    }
    let nj = r.count(8)?;
    let joints = (0..nj).map(|_| r.u64()).collect::<R<Vec<_>>>()?;
    let ib = r.f32s()?;
    if ib.len() % 16 != 0 {
        return Err("the inverse bind matrices are not whole".into());
    }
    let inverse_bind = ib
        .chunks_exact(16)
        .map(|c| Mat4::from_row_major(c.try_into().unwrap_or([0.0; 16])))
        .collect();
    let ns = r.count(4)?;
    let start = r
        .take(ns * 4)?
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let nij = r.count(2)?;
    let ij = r
        .take(nij * 2)?
        .chunks_exact(2)
        .map(|c| u16::from_le_bytes([c[0], c[1]]))
        .collect();
    let influences = Influences {
        start,
        joints: ij,
        weights: r.f32s()?,
    };
    let na = r.count(16)?;
    let mut animations = Vec::with_capacity(na);
    for _ in 0..na {
        let name = r.str()?;
        let nc = r.count(40)?;
        let mut channels = Vec::with_capacity(nc);
        for _ in 0..nc {
            let node = r.u64()?;
            let path = match r.u64()? {
                0 => Path::Translation,
                1 => Path::Rotation,
                2 => Path::Scale,
                _ => return Err("an unknown channel path".into()),
            };
            let interpolation = match r.u64()? {
                0 => Interpolation::Linear,
                1 => Interpolation::Step,
                2 => Interpolation::CubicSpline,
                _ => return Err("an unknown interpolation".into()),
            };
            let times = r.f32s()?;
            let v = r.f32s()?;
            if v.len() % 4 != 0 {
                return Err("channel values are not whole".into());
            }
            let values = v
                .chunks_exact(4)
                .map(|c| [c[0], c[1], c[2], c[3]])
                .collect();
            channels.push(Channel {
                node,
                path,
                interpolation,
                times,
                values,
            });
        }
        animations.push(Animation { name, channels });
    }
    if !r.0.is_empty() {
        return Err("bytes after the pickled rig".into());
    }
    let mesh = Mesh {
        positions,
        normals,
        triangles,
    };
    Rig::new(
        name,
        mesh,
        nodes,
        joints,
        inverse_bind,
        influences,
        animations,
    )
    .map_err(|e| e.to_string())
}
