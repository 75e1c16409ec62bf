//! Shapes (trianglemesh, plymesh, sphere, disk) and their area lights.

use super::material::BuiltMaterials;
use super::mesh::{bilinear_triangles, make_mesh, push_mesh};
use super::Warnings;
use crate::geometry::subdiv::loop_subdivide;
use crate::geometry::{Cylinder, Disk, Prim, Sphere};
use crate::light::Light;
use crate::scene::{Instance, InstanceSet, PrimInfo, Shapes, NO_LIGHT};
use lumis_math::Transform;
use lumis_scene::{Diagnostic, SceneDesc, ShapeDesc};

pub fn build_shapes(
    desc: &SceneDesc,
    mats: &BuiltMaterials,
    shapes: &mut Shapes,
    lights: &mut Vec<Light>,
    w: &mut Warnings,
) -> Result<(Vec<PrimInfo>, InstanceSet), Diagnostic> {
    let prims = add_shapes(desc, &desc.shapes, mats, shapes, lights, w)?;
    // Objects: built once, in the space of their shapes' own transforms
    // (area lights were already refused by the parser, as pbrt-v4 does).
    let mut set = InstanceSet::default();
    for o in &desc.objects {
        let before = lights.len();
        let prims = add_shapes(desc, &o.shapes, mats, shapes, lights, w)?;
        debug_assert_eq!(lights.len(), before, "objects carry no area lights");
        set.objects.push(prims);
    }
    for inst in &desc.instances {
        if set.objects[inst.object as usize].is_empty() {
            w.push(Diagnostic::warning(
                &inst.loc,
                format!(
                    "object `{}` has no shapes; this instance adds nothing",
                    desc.objects[inst.object as usize].name
                ),
            ));
            continue;
        }
        set.instances.push(Instance {
            object: inst.object,
            world_from_object: inst.world_from_object,
        });
    }
    Ok((prims, set))
}

fn add_shapes(
    desc: &SceneDesc,
    list: &[ShapeDesc],
    mats: &BuiltMaterials,
    shapes: &mut Shapes,
    lights: &mut Vec<Light>,
    w: &mut Warnings,
) -> Result<Vec<PrimInfo>, Diagnostic> {
    // Material indices follow the description's order; named ones resolve here.
    let mut prims = Vec::new();
    for s in list {
        let material = match desc.material(&s.material)? {
            None => mats.default,
            Some(m) => desc
                .materials
                .iter()
                .position(|x| std::ptr::eq(x, m))
                .map(|i| i as u32)
                .unwrap_or(mats.default),
        };
        let new_prims = build_shape(desc, s, shapes, w)?;
        if new_prims.is_empty() {
            continue;
        }
        let first_light = lights.len() as u32;
        if let Some(al) = &s.area_light {
            let built = super::area_lights::area_lights(desc, al, shapes, &new_prims, w)?;
            lights.extend(built.into_iter().map(Light::Area));
        }
        let has_light = lights.len() as u32 > first_light;
        for (i, &p) in new_prims.iter().enumerate() {
            let light = if has_light {
                first_light + i as u32
            } else {
                NO_LIGHT
            };
            prims.push(PrimInfo {
                prim: p,
                material,
                light,
            });
        }
    }
    Ok(prims)
}

/// Converts one shape into primitives (several for meshes).
fn build_shape(
    desc: &SceneDesc,
    s: &ShapeDesc,
    shapes: &mut Shapes,
    w: &mut Warnings,
) -> Result<Vec<Prim>, Diagnostic> {
    let e = &s.entity;
    let p = &e.params;
    w.unsupported(p, &["alpha", "emissionfilename"], "shape", "ignored");
    let xf = s.object_to_world;
    let flip = s.reverse_orientation ^ xf.swaps_handedness();
    let prims = match e.ty.as_str() {
        "trianglemesh" => {
            let pos = p
                .get_point3s("P")?
                .ok_or_else(|| Diagnostic::error(&e.loc, "trianglemesh needs \"point3 P\""))?;
            let indices = match p.get_ints("indices")? {
                Some(i) => i,
                None if pos.len() == 3 => vec![0, 1, 2],
                None => return Err(Diagnostic::error(
                    &e.loc,
                    "trianglemesh needs \"integer indices\" (only a single triangle may omit them)",
                )),
            };
            let normals = p.get_normals("N")?;
            let uvs = p.get_point2s("uv")?;
            p.mark_used("S");
            p.mark_used("faceIndices");
            w.unused(
                p,
                "shape \"trianglemesh\"",
                &["P", "indices", "N", "uv", "S", "faceIndices"],
            );
            let mesh = make_mesh(e, pos, normals, uvs, indices, &xf, flip)?;
            push_mesh(shapes, mesh)
        }
        "plymesh" => {
            let file = p.get_string("filename", "")?;
            if file.is_empty() {
                return Err(Diagnostic::error(
                    &e.loc,
                    "plymesh needs \"string filename\"",
                ));
            }
            let path = desc.resolve_path(&file);
            let loc = p.loc_of("filename").unwrap_or(e.loc.clone());
            let ply = lumis_scene::ply::read_ply(&path)
                .map_err(|err| Diagnostic::error(&loc, format!("{err}")))?;
            w.unsupported(p, &["displacement", "edgelength"], "plymesh", "ignored");
            w.unused(p, "shape \"plymesh\"", &["filename"]);
            let indices = ply.indices.iter().map(|&i| i as i32).collect();
            let mesh = make_mesh(e, ply.positions, ply.normals, ply.uvs, indices, &xf, flip)?;
            push_mesh(shapes, mesh)
        }
        "bilinearmesh" => {
            let pos = p
                .get_point3s("P")?
                .ok_or_else(|| Diagnostic::error(&e.loc, "bilinearmesh needs \"point3 P\""))?;
            let indices = match p.get_ints("indices")? {
                Some(i) => i,
                None if pos.len() == 4 => vec![0, 1, 2, 3],
                None => return Err(Diagnostic::error(
                    &e.loc,
                    "bilinearmesh needs \"integer indices\" (only a single patch may omit them)",
                )),
            };
            let uvs = p.get_point2s("uv")?;
            let normals = p.get_normals("N")?;
            p.mark_used("faceIndices");
            w.unused(
                p,
                "shape \"bilinearmesh\"",
                &["P", "indices", "uv", "N", "faceIndices"],
            );
            if !indices.len().is_multiple_of(4) {
                return Err(Diagnostic::error(
                    &e.loc,
                    format!(
                        "bilinearmesh: {} indices is not a multiple of 4",
                        indices.len()
                    ),
                ));
            }
            // Checked as a mesh (index range, uv and normal counts) before use.
            let tris: Vec<i32> = indices
                .chunks(4)
                .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
                .collect();
            let checked = make_mesh(e, pos, normals, uvs, tris, &Transform::IDENTITY, false)?;
            let idx: Vec<u32> = indices.iter().map(|&i| i as u32).collect();
            let (bp, buv, bn, bi) = bilinear_triangles(
                &checked.positions,
                &idx,
                checked.uvs.as_deref(),
                checked.normals.as_deref(),
            );
            let mesh = make_mesh(e, bp, bn, Some(buv), bi, &xf, flip)?;
            push_mesh(shapes, mesh)
        }
        "loopsubdiv" => {
            let pos = p
                .get_point3s("P")?
                .ok_or_else(|| Diagnostic::error(&e.loc, "loopsubdiv needs \"point3 P\""))?;
            let indices = p
                .get_ints("indices")?
                .ok_or_else(|| Diagnostic::error(&e.loc, "loopsubdiv needs \"integer indices\""))?;
            let levels = p.get_int("levels", 3)?;
            w.unused(p, "shape \"loopsubdiv\"", &["P", "indices", "levels"]);
            if !(0..=12).contains(&levels) {
                return Err(Diagnostic::error(
                    &p.loc_of("levels").unwrap_or(e.loc.clone()),
                    format!("loopsubdiv levels must be 0 to 12, found {levels}"),
                ));
            }
            // Checked as a mesh first (index range, multiple of 3).
            let mesh = make_mesh(e, pos, None, None, indices, &Transform::IDENTITY, false)?;
            let sub = loop_subdivide(&mesh.positions, &mesh.indices, levels as u32)
                .map_err(|m| Diagnostic::error(&e.loc, format!("loopsubdiv: {m}")))?;
            let indices = sub.indices.iter().map(|&i| i as i32).collect();
            let mesh = make_mesh(
                e,
                sub.positions,
                Some(sub.normals),
                None,
                indices,
                &xf,
                flip,
            )?;
            push_mesh(shapes, mesh)
        }
        "sphere" => {
            let radius = p.get_float("radius", 1.0)?;
            let zmin = p.get_float("zmin", -radius)?;
            let zmax = p.get_float("zmax", radius)?;
            let phimax = p.get_float("phimax", 360.0)?;
            w.unused(p, "shape \"sphere\"", &["radius", "zmin", "zmax", "phimax"]);
            if !(radius > 0.0) {
                return Err(Diagnostic::error(
                    &p.loc_of("radius").unwrap_or(e.loc.clone()),
                    "sphere radius must be positive",
                ));
            }
            let sphere = Sphere::partial(xf, radius, zmin, zmax, phimax, s.reverse_orientation);
            if !(sphere.area() > 0.0) {
                return Err(Diagnostic::error(
                    &e.loc,
                    "this sphere has no surface left (zmin = zmax or phimax = 0)",
                ));
            }
            let i = shapes.spheres.len() as u32;
            shapes.spheres.push(sphere);
            vec![Prim::Sphere(i)]
        }
        "cylinder" => {
            let radius = p.get_float("radius", 1.0)?;
            let zmin = p.get_float("zmin", -1.0)?;
            let zmax = p.get_float("zmax", 1.0)?;
            let phimax = p.get_float("phimax", 360.0)?;
            w.unused(
                p,
                "shape \"cylinder\"",
                &["radius", "zmin", "zmax", "phimax"],
            );
            let c = Cylinder::new(xf, radius, zmin, zmax, phimax, s.reverse_orientation);
            if !(radius > 0.0 && c.area() > 0.0) {
                return Err(Diagnostic::error(
                    &e.loc,
                    "cylinder needs radius > 0, zmin != zmax and phimax > 0",
                ));
            }
            let i = shapes.cylinders.len() as u32;
            shapes.cylinders.push(c);
            vec![Prim::Cylinder(i)]
        }
        "disk" => {
            let height = p.get_float("height", 0.0)?;
            let radius = p.get_float("radius", 1.0)?;
            let inner = p.get_float("innerradius", 0.0)?;
            if p.get_float("phimax", 360.0)? < 360.0 {
                w.push(Diagnostic::warning(
                    &e.loc,
                    "partial disks (phimax) are not supported yet; rendering the full disk",
                ));
            }
            w.unused(
                p,
                "shape \"disk\"",
                &["height", "radius", "innerradius", "phimax"],
            );
            if !(radius > 0.0 && inner >= 0.0 && inner < radius) {
                return Err(Diagnostic::error(
                    &e.loc,
                    "disk needs radius > innerradius >= 0",
                ));
            }
            let i = shapes.disks.len() as u32;
            shapes
                .disks
                .push(Disk::new(xf, height, radius, inner, s.reverse_orientation));
            vec![Prim::Disk(i)]
        }
        other => {
            for q in p.unused() {
                q.mark_used();
            }
            w.push(Diagnostic::warning(
                &e.loc,
                format!("shape `{other}` is not supported yet; skipped"),
            ));
            Vec::new()
        }
    };
    Ok(prims)
}
