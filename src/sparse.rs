//! Sparse matrices in coordinate form, below both the assembly that fills
//! them and the linear algebra that turns them into factorisable matrices.

/// Coordinate-format entries over the free DOFs. Duplicates are summed when
/// the matrix is built, so element matrices are appended as they come.
#[derive(Clone, Debug, Default)]
pub struct Triplets {
    pub rows: Vec<usize>,
    pub cols: Vec<usize>,
    pub vals: Vec<f64>,
}

impl Triplets {
    pub fn len(&self) -> usize {
        self.vals.len()
    }

    pub fn is_empty(&self) -> bool {
        self.vals.is_empty()
    }
}
