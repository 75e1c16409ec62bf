//! The driver's pass when the pixel filter splats ([`Filter::splat`]): the
//! reconstruction of Mitsuba 3 and pbrt-v3 instead of pbrt-v4's filter
//! importance sampling.
//!
//! Each camera sample is taken at a point uniform in its own pixel and
//! counts in every pixel whose filter reaches that point, weighted by the
//! filter's density there (`Filter::pdf`); a pixel's value is its weighted
//! sum over the sum of the weights (`Film::weights`). A pixel thus averages
//! its neighbours' samples as well as its own (about `4 pi sigma^2`
//! pixels' worth for a Gaussian: 3.1 times the samples at pbrt's default
//! `sigma` 0.5), where importance sampling gives each sample to one pixel.
//! The same filtered image in the limit (the ratio's bias falls as one over
//! the samples), with less noise per sample, correlated over the filter's
//! radius.
//!
//! Pixels beyond the window (the crop, or the film) within the filter's
//! reach are sampled too, as Mitsuba's `sample_border` does, so the edge
//! pixels' filter is whole: their samples count only in the window's pixels
//! (their light splats and bad samples are not the window's; their rays
//! are counted; beyond the film, the integrator sees them as the nearest
//! film pixel's). They are the samples a larger window would take there, so
//! a crop's pixels are those of the whole film, bit for bit.
//!
//! Per sample index, the rows are traced in parallel into a buffer of one
//! sample per pixel; then each pixel gathers its neighbours' samples, in a
//! fixed order, and adds their weighted sum as one sample and their weights
//! to its weight: the image does not depend on the thread count, and the
//! sums merge and resume as the film's always do. A dropped (non-finite)
//! sample counts as black in its neighbours.

use super::driver::{add_pass_splats, add_rows, take_sample, Pass, RenderSettings, Splat, Tally};
use crate::film::{exact, Film};
use crate::scene::Scene;
use lumis_math::{Rgb, Sampler, Vec2};
use rayon::prelude::*;
use std::ops::Range;

/// Samples `indices` of every pixel of the crop, splatted.
pub(super) fn render_pass<P: Pass>(
    scene: &Scene,
    pass: &P,
    settings: &RenderSettings,
    film: &mut Film,
    indices: Range<u32>,
) -> Tally {
    let f = &settings.filter;
    let b = settings.crop;
    let (w, h) = (b.width() as usize, b.height() as usize);
    let (rx, ry) = f.reach();
    // The last film pixel's coordinates.
    let (fw, fh) = (
        film.full_resolution.0 as i32 - 1,
        film.full_resolution.1 as i32 - 1,
    );
    // The window and a border of the filter's reach around it.
    let (ew, eh) = (w + 2 * rx, h + 2 * ry);
    // Per pixel of the current index: its sample's radiance, and the
    // filter's factors at the pixels it may reach: `wx[k]` in the column
    // `k - rx` from its own, `wy` alike (the filter is separable).
    let (nx, ny) = (2 * rx + 1, 2 * ry + 1);
    let mut taken = vec![Rgb::BLACK; ew * eh];
    let mut wxs = vec![0.0f32; ew * eh * nx];
    let mut wys = vec![0.0f32; ew * eh * ny];
    let mut tally = Tally::default();
    film.weights.resize(film.pixels.len(), 0);
    for s in indices.clone() {
        let rows: Vec<(Tally, Vec<Splat>)> = taken
            .par_chunks_mut(ew.max(1))
            .zip(wxs.par_chunks_mut((ew * nx).max(1)))
            .zip(wys.par_chunks_mut((ew * ny).max(1)))
            .enumerate()
            .map(|(er, ((out, wx), wy))| {
                // Raster coordinates, negative ones wrapped (a pixel's
                // random numbers only hash them).
                let py = (b.y0 as i64 + er as i64 - ry as i64) as i32;
                let row_inside = (ry..ry + h).contains(&er);
                let mut sampler = Sampler::new(settings.sampler, settings.seed);
                let (mut t, mut border) = (Tally::default(), Tally::default());
                let (mut splats, mut dropped) = (Vec::new(), Vec::new());
                for (ec, (o, (wx, wy))) in out
                    .iter_mut()
                    .zip(wx.chunks_exact_mut(nx).zip(wy.chunks_exact_mut(ny)))
                    .enumerate()
                {
                    let px = (b.x0 as i64 + ec as i64 - rx as i64) as i32;
                    sampler.start_pixel_sample(px as u32, py as u32, s);
                    // The integrator sees a sample beyond the film as its
                    // nearest film pixel's (whose per-pixel state, such as
                    // `vcm`'s light subpaths, it shares).
                    let at = (px.clamp(0, fw) as u32, py.clamp(0, fh) as u32, s);
                    let u = sampler.get_2d();
                    let p_film = Vec2::new(px as f32 + u.x, py as f32 + u.y);
                    let inside = row_inside && (rx..rx + w).contains(&ec);
                    let (t, sp) = match inside {
                        true => (&mut t, &mut splats),
                        false => (&mut border, &mut dropped),
                    };
                    let l = take_sample(scene, pass, settings, &mut sampler, at, p_film, t, sp);
                    dropped.clear();
                    *o = l.unwrap_or(Rgb::BLACK);
                    // Offsets from the centres of the pixels `k - reach` away.
                    for (k, v) in wx.iter_mut().enumerate() {
                        *v = f.pdf_axis(true, u.x - 0.5 - (k as f32 - rx as f32));
                    }
                    for (k, v) in wy.iter_mut().enumerate() {
                        *v = f.pdf_axis(false, u.y - 0.5 - (k as f32 - ry as f32));
                    }
                }
                t.add_rays(&border);
                (t, splats)
            })
            .collect();
        add_rows(&mut tally, film, rows, settings.clamp);
        let (taken, wxs, wys) = (taken.as_slice(), wxs.as_slice(), wys.as_slice());
        film.pixels
            .par_chunks_mut(w.max(1))
            .zip(film.weights.par_chunks_mut(w.max(1)))
            .enumerate()
            .for_each(|(row, (pixels, weights))| {
                for (col, (pixel, weight)) in pixels.iter_mut().zip(weights).enumerate() {
                    let (mut sum, mut total) = (Rgb::BLACK, 0.0f32);
                    // Window pixel (col, row) is (col + rx, row + ry) of
                    // `taken`; the sample `i` columns and `j` rows into the
                    // block from (col, row) is `i - rx` columns from it:
                    // its factors are `wx[2 rx - i]` and `wy[2 ry - j]`.
                    for j in 0..ny {
                        let q = (row + j) * ew + col;
                        let (l, wx, wy) = (
                            &taken[q..q + nx],
                            &wxs[q * nx..(q + nx) * nx],
                            &wys[q * ny..(q + nx) * ny],
                        );
                        for i in 0..nx {
                            let f = wx[i * nx + nx - 1 - i] * wy[i * ny + ny - 1 - j];
                            sum += l[i] * f;
                            total += f;
                        }
                    }
                    pixel.add(sum);
                    *weight = weight.wrapping_add(exact::sum_units(total as f64));
                }
            });
    }
    add_pass_splats(pass, settings, film, indices.len() as f32);
    tally
}
