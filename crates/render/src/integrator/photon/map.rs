//! The photon map: photons and a kd-tree over their positions
//! (`kdtree.rs`) for k-nearest and fixed-radius queries. The photons are
//! reordered into the tree's leaf order so that a query's photons are close
//! in memory.

pub(crate) use super::kdtree::{dist2, inclusive, KdTree};
use super::photon::Photon;
use lumis_math::{Rgb, Vec3, PI};

/// Points per leaf at most (the average is between half and all of it):
/// measured best for k = 50 among 1M photons.
const MAP_LEAF: usize = 64;

/// Photons and the kd-tree over their positions. `Send + Sync`.
///
/// The photons are stored in the tree's leaf order (not the order given to
/// [`PhotonMap::build`]) so that a query's photons are close in memory;
/// [`PhotonMap::original_index`] maps back.
#[derive(Debug)]
pub struct PhotonMap {
    photons: Vec<Photon>,
    /// Index in the input of each stored photon.
    order: Vec<u32>,
    tree: KdTree,
    emitted: u64,
}

impl PhotonMap {
    /// `emitted`: photons emitted in the pass that built this map (the N of
    /// the estimates). Query results index [`PhotonMap::photons`].
    pub fn build(photons: Vec<Photon>, emitted: u64) -> PhotonMap {
        let mut tree = KdTree::build(photons.iter().map(Photon::pos), MAP_LEAF);
        let order = tree.reindex_to_leaf_order();
        let photons = order.iter().map(|&i| photons[i as usize]).collect();
        PhotonMap {
            photons,
            order,
            tree,
            emitted,
        }
    }

    /// Index in the `Vec` given to [`PhotonMap::build`] of stored photon `i`.
    #[inline]
    pub fn original_index(&self, i: u32) -> u32 {
        self.order[i as usize]
    }

    pub fn len(&self) -> usize {
        self.photons.len()
    }

    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }

    pub fn emitted(&self) -> u64 {
        self.emitted
    }

    pub fn memory_bytes(&self) -> usize {
        self.photons.capacity() * std::mem::size_of::<Photon>()
            + self.order.capacity() * 4
            + self.tree.memory_bytes()
    }

    #[inline]
    pub fn photon(&self, i: u32) -> &Photon {
        &self.photons[i as usize]
    }

    pub fn photons(&self) -> &[Photon] {
        &self.photons
    }

    /// Up to `k` nearest photons within `max_radius` of `p`, written into
    /// `out` as (index, squared distance) in no particular order (a max-heap).
    /// Returns the squared radius of the disc they cover: the largest squared
    /// distance among them if `k` were found, else `max_radius^2`.
    pub fn knn(&self, p: Vec3, k: usize, max_radius: f32, out: &mut Vec<(u32, f32)>) -> f32 {
        out.clear();
        let r2 = max_radius * max_radius;
        if k == 0 || !(max_radius >= 0.0) {
            return r2.max(0.0);
        }
        let mut bound = inclusive(r2);
        self.tree
            .for_each_within(p.to_array(), &mut bound, |i, d2, bound| {
                if out.len() < k {
                    heap_push(out, (i, d2));
                    if out.len() == k {
                        *bound = out[0].1;
                    }
                } else {
                    heap_replace_top(out, (i, d2));
                    *bound = out[0].1;
                }
            });
        if out.len() == k {
            out[0].1
        } else {
            r2
        }
    }

    /// All photons within `radius` of `p` (distance <= radius), in no order.
    pub fn within(&self, p: Vec3, radius: f32, out: &mut Vec<(u32, f32)>) {
        out.clear();
        if !(radius >= 0.0) {
            return;
        }
        let mut bound = inclusive(radius * radius);
        self.tree
            .for_each_within(p.to_array(), &mut bound, |i, d2, _| out.push((i, d2)));
    }
}

/// Irradiance estimate at `p` with normal `n` from the `k` nearest photons
/// within `max_radius`, counting those arriving from `n`'s side
/// (`dot(dir, n) > 0`): `E = sum(power) / (pi r^2)`. Returns `(E, r^2)`.
pub fn irradiance_knn(
    map: &PhotonMap,
    p: Vec3,
    n: Vec3,
    k: usize,
    max_radius: f32,
    scratch: &mut Vec<(u32, f32)>,
) -> (Rgb, f32) {
    let r2 = map.knn(p, k, max_radius, scratch);
    let mut sum = Rgb::BLACK;
    for &(i, _) in scratch.iter() {
        let ph = map.photon(i);
        if ph.dir_unnormalized().dot(n) > 0.0 {
            sum += ph.power();
        }
    }
    if r2 > 0.0 && sum != Rgb::BLACK {
        (sum / (PI * r2), r2)
    } else {
        (Rgb::BLACK, r2)
    }
}

/// Irradiance estimate at `p` with normal `n` from every photon within
/// `radius` arriving from `n`'s side, except one lying exactly at `p`:
/// `E = sum(power) / (pi r^2)`. (A point that is itself a photon of the
/// map would otherwise always count itself, however small the disc.)
pub fn irradiance_within(
    map: &PhotonMap,
    p: Vec3,
    n: Vec3,
    radius: f32,
    scratch: &mut Vec<(u32, f32)>,
) -> Rgb {
    map.within(p, radius, scratch);
    let mut sum = Rgb::BLACK;
    for &(i, d2) in scratch.iter() {
        let ph = map.photon(i);
        if d2 > 0.0 && ph.dir_unnormalized().dot(n) > 0.0 {
            sum += ph.power();
        }
    }
    if radius > 0.0 {
        sum / (PI * radius * radius)
    } else {
        Rgb::BLACK
    }
}

/// Max-heap on the distance.
#[inline]
fn heap_push(h: &mut Vec<(u32, f32)>, e: (u32, f32)) {
    let mut i = h.len();
    h.push(e);
    while i > 0 {
        let parent = (i - 1) / 2;
        if h[parent].1 >= e.1 {
            break;
        }
        h[i] = h[parent];
        i = parent;
    }
    h[i] = e;
}

#[inline]
fn heap_replace_top(h: &mut [(u32, f32)], e: (u32, f32)) {
    let n = h.len();
    let mut i = 0;
    loop {
        let l = 2 * i + 1;
        if l >= n {
            break;
        }
        let c = if l + 1 < n && h[l + 1].1 > h[l].1 {
            l + 1
        } else {
            l
        };
        if h[c].1 <= e.1 {
            break;
        }
        h[i] = h[c];
        i = c;
    }
    h[i] = e;
}
