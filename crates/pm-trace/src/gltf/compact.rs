//! Keeping only the vertices a primitive's triangles use: one triangle placed a hundred times
//! from an accessor of 100,000 vertices is three vertices per placement to weld and store,
//! not 100,000.

/// Renumbers `triangles` to use only the vertices they name, of `vertex_count`, and returns
/// the original indices of the vertices kept, in increasing order (so the renumbering is the
/// same on every run).
pub(super) fn keep_referenced(triangles: &mut [[u32; 3]], vertex_count: usize) -> Vec<u32> {
    let mut new_index = vec![u32::MAX; vertex_count];
    for &i in triangles.iter().flatten() {
        new_index[i as usize] = 0;
    }
    let mut kept = Vec::new();
    for (old, slot) in new_index.iter_mut().enumerate() {
        if *slot == 0 {
            *slot = kept.len() as u32;
            kept.push(old as u32);
        }
    }
    for i in triangles.iter_mut().flatten() {
        *i = new_index[*i as usize];
    }
    kept
}

/// The values of the kept vertices, in the order [`keep_referenced`] gave.
pub(super) fn gather<T: Copy>(values: &[T], kept: &[u32]) -> Vec<T> {
    kept.iter().map(|&i| values[i as usize]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_named_vertices_stay_in_their_order() {
        let mut triangles = [[7u32, 2, 9], [9, 2, 4]];
        let kept = keep_referenced(&mut triangles, 10);
        assert_eq!(kept, [2, 4, 7, 9]);
        assert_eq!(triangles, [[2, 0, 3], [3, 0, 1]]);
        let values: Vec<u32> = (0..10).map(|i| i * 10).collect();
        assert_eq!(gather(&values, &kept), [20, 40, 70, 90]);
        let mut none: [[u32; 3]; 0] = [];
        assert!(keep_referenced(&mut none, 5).is_empty());
    }
}
