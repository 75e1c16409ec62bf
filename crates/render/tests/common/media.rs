//! Scenes and statistics the media tests share.

use super::{header, region_mean_and_se};

/// Inside a sphere of radius 1 filled with `medium`, seen from its centre;
/// the sphere is `wall` (an area light or a black surface).
pub fn sphere_of(medium: &str, wall: &str) -> String {
    format!(
        r#"Integrator "path" "integer maxdepth" [ 100000 ]
{}
MediumInterface "" "fog"
LookAt 0 0 0  0.3 0.2 -1  0 1 0
Camera "perspective" "float fov" [ 90 ]
WorldBegin
{medium}
{wall}
Material "diffuse" "rgb reflectance" [ 0 0 0 ]
MediumInterface "fog" ""
Shape "sphere" "float radius" [ 1 ]
"#,
        header(16)
    )
}

/// Per channel, the film's mean and its standard error.
pub fn per_channel(film: &lumis_render::film::Film) -> [(f64, f64); 3] {
    [0, 1, 2].map(|c| region_mean_and_se(film, Some(c)))
}
