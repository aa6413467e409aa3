//! What can stop an experiment.

/// An experiment's error.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// An operation of the core failed.
    #[error(transparent)]
    Chasles(#[from] chasles::Error),
    /// A picture could not be encoded.
    #[error("picture: {0}")]
    Picture(#[from] chasles_viz::EncodeError),
    /// A built-in key set of that name does not exist.
    #[error("no built-in key set '{0}'")]
    NoKeySet(String),
    /// A measurement over random samples was asked for none.
    #[error("at least one random sample is needed")]
    NoSamples,
}

/// `Result` with [`Error`].
pub type Result<T> = std::result::Result<T, Error>;

/// [`Error::NoSamples`] when `samples` is 0.
pub fn need_samples(samples: usize) -> Result<()> {
    if samples == 0 {
        Err(Error::NoSamples)
    } else {
        Ok(())
    }
}
