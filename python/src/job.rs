//! [`Job`]: a `RenderJob` made from keyword arguments as the CLI makes one
//! from its flags (`lumis_render::session::RenderFlags`): the same fields, the same
//! parameter overrides, each labelled with its keyword (`resolution=`) so
//! the library's errors point at it.

use crate::params;
use lumis_render::session::{Accel, RenderJob};
use lumis_scene::{Override, Overrides};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple};
use std::path::PathBuf;

/// The keywords that set a field of the job, then those that override
/// the scene file, in the order the CLI applies its flags.
const JOB_KEYS: &[&str] = &[
    "spp", "time", "seed", "threads", "clamp", "accel", "output", "exposure",
];
const SCENE_KEYS: &[&str] = &[
    "resolution",
    "crop",
    "sampler",
    "filter_splat",
    "integrator",
    "maxdepth",
];

/// A render job: the scene, parameters layered over the file's, seed,
/// budget, threads and outputs, as plain data. `to_json()` gives the same
/// JSON the CLI stores in its checkpoints; `Job.from_json()` reads it back.
#[pyclass(module = "lumis", name = "Job", from_py_object)]
#[derive(Clone)]
pub struct Job {
    pub job: RenderJob,
}

#[pymethods]
impl Job {
    /// `Job(scene=None, **params)`: a job for the scene file `scene` (None:
    /// the built-in default scene), made in the current folder; `params` as
    /// for `lumis.render`.
    #[new]
    #[pyo3(signature = (scene = None, **params))]
    fn new(scene: Option<PathBuf>, params: Option<&Bound<'_, PyDict>>) -> PyResult<Job> {
        let mut job = Job {
            job: RenderJob::new(scene),
        };
        if let Some(p) = params {
            job.update(p)?;
        }
        Ok(job)
    }

    /// Sets `params` (later values win over earlier ones); a parameter
    /// given as None is left as it is.
    #[pyo3(signature = (**params))]
    fn set(&mut self, params: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
        if let Some(p) = params {
            // All or nothing.
            let mut j = self.clone();
            j.update(p)?;
            *self = j;
        }
        Ok(())
    }

    /// A copy with `params` set.
    #[pyo3(signature = (**params))]
    fn with_params(&self, params: Option<&Bound<'_, PyDict>>) -> PyResult<Job> {
        let mut j = self.clone();
        j.set(params)?;
        Ok(j)
    }

    fn copy(&self) -> Job {
        self.clone()
    }

    fn __copy__(&self) -> Job {
        self.clone()
    }

    fn __deepcopy__(&self, _memo: &Bound<'_, PyAny>) -> Job {
        self.clone()
    }

    /// The job as JSON (the format of the CLI's checkpoints).
    fn to_json(&self) -> String {
        self.job.to_json()
    }

    /// The job a JSON text describes (`ValueError` if it is not one).
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Job> {
        let job = RenderJob::from_json(text).map_err(PyValueError::new_err)?;
        Ok(Job { job })
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        match other.cast::<Job>() {
            Ok(o) => o.borrow().job == self.job,
            Err(_) => false,
        }
    }

    fn __repr__(&self) -> String {
        let scene = match &self.job.scene {
            Some(p) => format!("{:?}", p.display().to_string()),
            None => "None".into(),
        };
        let mut parts = vec![scene];
        if let Some(s) = self.job.budget.spp {
            parts.push(format!("spp={s}"));
        }
        if let Some(t) = self.job.budget.time {
            parts.push(format!("time={t}"));
        }
        parts.push(format!("seed={}", self.job.seed));
        for o in &self.job.overrides.items {
            let what = match &o.ty {
                Some(t) => format!("{} {t:?}", o.directive),
                None => format!("{} {}", o.directive, o.params),
            };
            parts.push(format!("[{}: {what}]", o.origin));
        }
        format!("Job({})", parts.join(", "))
    }

    /// Pickling goes through the JSON.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let from_json = py.get_type::<Job>().getattr("from_json")?;
        let args = PyTuple::new(py, [slf.borrow().to_json()])?;
        PyTuple::new(py, [from_json.into_any(), args.into_any()])
    }

    /// The scene file (None: the built-in default scene).
    #[getter]
    fn scene(&self) -> Option<PathBuf> {
        self.job.scene.clone()
    }
    #[setter]
    fn set_scene(&mut self, v: Option<PathBuf>) {
        self.job.scene = v;
    }

    #[getter]
    fn seed(&self) -> u64 {
        self.job.seed
    }
    #[setter]
    fn set_seed(&mut self, v: u64) {
        self.job.seed = v;
    }

    /// Samples per pixel (None: the scene's, or unbounded with only a time budget).
    #[getter]
    fn spp(&self) -> Option<u32> {
        self.job.budget.spp
    }
    #[setter]
    fn set_spp(&mut self, v: Option<u32>) -> PyResult<()> {
        let mut j = self.clone();
        j.job.budget.spp = v;
        j.check()?;
        *self = j;
        Ok(())
    }

    /// Wall-clock budget in seconds (None: no time limit).
    #[getter]
    fn time(&self) -> Option<f64> {
        self.job.budget.time
    }
    #[setter]
    fn set_time(&mut self, v: Option<f64>) -> PyResult<()> {
        let mut j = self.clone();
        j.job.budget.time = v;
        j.check()?;
        *self = j;
        Ok(())
    }

    /// Worker threads (0: all cores); the image does not depend on it.
    #[getter]
    fn threads(&self) -> usize {
        self.job.threads
    }
    #[setter]
    fn set_threads(&mut self, v: usize) {
        self.job.threads = v;
    }

    #[getter]
    fn clamp(&self) -> Option<f32> {
        self.job.clamp
    }
    #[setter]
    fn set_clamp(&mut self, v: Option<f32>) {
        self.job.clamp = v;
    }

    /// `"bvh"` or `"embree"`.
    #[getter]
    fn accel(&self) -> &'static str {
        match self.job.accel {
            Accel::Bvh => "bvh",
            Accel::Embree => "embree",
        }
    }
    #[setter]
    fn set_accel(&mut self, v: &str) -> PyResult<()> {
        self.job.accel = accel(v)?;
        Ok(())
    }

    /// Images the render writes (empty: none from Python).
    #[getter]
    fn outputs(&self) -> Vec<PathBuf> {
        self.job.outputs.clone()
    }
    #[setter]
    fn set_outputs(&mut self, v: Vec<PathBuf>) {
        self.job.outputs = v;
    }

    #[getter]
    fn exposure(&self) -> f32 {
        self.job.exposure
    }
    #[setter]
    fn set_exposure(&mut self, v: f32) {
        self.job.exposure = v;
    }

    /// A partial render: passes `(start, end)` of the render the rest of
    /// the job describes (one sample per pixel each), or None for all.
    #[getter]
    fn passes(&self) -> Option<(u32, u32)> {
        self.job.passes.as_ref().map(|r| (r.start, r.end))
    }
    #[setter]
    fn set_passes(&mut self, v: Option<(u32, u32)>) -> PyResult<()> {
        let mut j = self.clone();
        j.job.passes = v.map(|(a, b)| a..b);
        j.check()?;
        *self = j;
        Ok(())
    }

    /// The folder relative paths resolve against.
    #[getter]
    fn dir(&self) -> PathBuf {
        self.job.dir.clone()
    }
    #[setter]
    fn set_dir(&mut self, v: PathBuf) {
        self.job.dir = v;
    }

    /// The parameters layered over the scene file's, as a list of dicts
    /// (`directive`, `type`, `params` in scene-file syntax, `origin`).
    #[getter]
    fn overrides<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for o in &self.job.overrides.items {
            let d = PyDict::new(py);
            d.set_item("directive", &o.directive)?;
            d.set_item("type", &o.ty)?;
            d.set_item("params", &o.params)?;
            d.set_item("origin", &o.origin)?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// The scene file resolved against the job's folder (None: the default scene).
    fn scene_path(&self) -> Option<PathBuf> {
        self.job.scene.as_ref().map(|p| self.job.resolve(p))
    }
}

impl Job {
    fn check(&self) -> PyResult<()> {
        self.job.check().map_err(PyValueError::new_err)
    }

    /// Applies keyword parameters: the job's fields, then the scene
    /// overrides in the CLI's order, then the integrators' parameters in
    /// table order; unknown keywords are refused with a suggestion.
    fn update(&mut self, params: &Bound<'_, PyDict>) -> PyResult<()> {
        let tables = params::all();
        let mut known: Vec<String> = JOB_KEYS.iter().map(|s| s.to_string()).collect();
        known.extend(SCENE_KEYS.iter().map(|s| s.to_string()));
        known.extend(tables.iter().map(|s| params::keyword(s)));
        for key in params.keys() {
            let key: String = key.extract()?;
            if !known.contains(&key) && params::find(&key).is_none() {
                let names: Vec<&str> = known.iter().map(String::as_str).collect();
                let hint = match lumis_scene::loc::suggest(&key, &names, 3) {
                    Some(s) => format!(" (did you mean `{s}`?)"),
                    None => String::new(),
                };
                return Err(PyTypeError::new_err(format!(
                    "unknown parameter `{key}`{hint}; the parameters are: {}",
                    names.join(", ")
                )));
            }
        }
        let get = |k: &str| -> PyResult<Option<Bound<'_, PyAny>>> {
            Ok(params.get_item(k)?.filter(|v| !v.is_none()))
        };
        for &k in JOB_KEYS {
            if let Some(v) = get(k)? {
                self.job_field(k, &v)
                    .map_err(|e| with_keyword(v.py(), k, e))?;
            }
        }
        for &k in SCENE_KEYS {
            if let Some(v) = get(k)? {
                let items = scene_override(k, &v).map_err(|e| with_keyword(v.py(), k, e))?;
                self.replace(&origin(k), items);
            }
        }
        for s in tables {
            let kw = params::keyword(s);
            // The keyword, or else the scene-file name.
            let v = match get(&kw)? {
                Some(v) => Some(v),
                None => get(s.name)?,
            };
            if let Some(v) = v {
                let text =
                    params::scene_text(&v, s.ty).map_err(|e| with_keyword(v.py(), &kw, e))?;
                let mut o = Overrides::default();
                o.param(
                    "Integrator",
                    &format!("{} {}", s.ty, s.name),
                    &text,
                    &origin(&kw),
                );
                self.replace(&origin(&kw), o.items);
            }
        }
        self.check()
    }

    /// Puts `items` in place of the overrides from `origin` (kept where
    /// they were when unchanged, so a job set twice alike stays equal).
    fn replace(&mut self, origin: &str, items: Vec<Override>) {
        let ov = &mut self.job.overrides.items;
        let old: Vec<&Override> = ov.iter().filter(|o| o.origin == origin).collect();
        if old.len() == items.len() && old.iter().zip(&items).all(|(a, b)| *a == b) {
            return;
        }
        ov.retain(|o| o.origin != origin);
        ov.extend(items);
    }

    fn job_field(&mut self, key: &str, v: &Bound<'_, PyAny>) -> PyResult<()> {
        let j = &mut self.job;
        match key {
            "spp" => j.budget.spp = Some(v.extract()?),
            "time" => j.budget.time = Some(v.extract()?),
            "seed" => j.seed = v.extract()?,
            "threads" => j.threads = v.extract()?,
            "clamp" => j.clamp = Some(v.extract()?),
            "accel" => j.accel = accel(&v.extract::<String>()?)?,
            "output" => {
                j.outputs = match v.cast::<PyString>() {
                    Ok(_) => vec![v.extract()?],
                    Err(_) => match v.extract::<PathBuf>() {
                        Ok(p) => vec![p],
                        Err(_) => v.extract()?,
                    },
                }
            }
            "exposure" => j.exposure = v.extract()?,
            _ => unreachable!("a job keyword"),
        }
        Ok(())
    }
}

/// The label of overrides from keyword `key`: their "file" in diagnostics.
fn origin(key: &str) -> String {
    format!("{key}=")
}

/// `e` with the keyword it came from.
fn with_keyword(py: Python<'_>, key: &str, e: PyErr) -> PyErr {
    let new = PyErr::from_type(e.get_type(py), format!("{key}: {}", e.value(py)));
    new.set_cause(py, Some(e));
    new
}

fn accel(name: &str) -> PyResult<Accel> {
    match name {
        "bvh" => Ok(Accel::Bvh),
        "embree" => Ok(Accel::Embree),
        other => Err(PyValueError::new_err(format!(
            "unknown accel `{other}`: expected `bvh` or `embree`"
        ))),
    }
}

/// The overrides keyword `key` (resolution, crop, sampler, filter_splat,
/// integrator, maxdepth) makes, as the CLI's flags make them.
fn scene_override(key: &str, v: &Bound<'_, PyAny>) -> PyResult<Vec<Override>> {
    let mut o = Overrides::default();
    let from = origin(key);
    match key {
        "resolution" => {
            let (w, h) = resolution(v)?;
            o.resolution_from(w, h, &from);
        }
        "crop" => {
            o.crop_from(fractions(v)?, &from);
        }
        "sampler" => {
            o.sampler_from(&v.extract::<String>()?, &from);
        }
        "filter_splat" => {
            o.filter_splat_from(v.extract()?, &from);
        }
        "integrator" => {
            o.integrator_from(&v.extract::<String>()?, &from);
        }
        "maxdepth" => {
            o.max_depth_from(v.extract()?, &from);
        }
        _ => unreachable!("a scene keyword"),
    }
    Ok(o.items)
}

/// `(w, h)` or `"WxH"`, at least 1x1.
fn resolution(v: &Bound<'_, PyAny>) -> PyResult<(u32, u32)> {
    let (w, h): (u32, u32) = match v.extract::<String>() {
        Ok(s) => {
            let bad = || PyValueError::new_err(format!("expected WxH, e.g. 640x480, found `{s}`"));
            let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
            (
                w.trim().parse().map_err(|_| bad())?,
                h.trim().parse().map_err(|_| bad())?,
            )
        }
        Err(_) => v.extract()?,
    };
    if w == 0 || h == 0 {
        return Err(PyValueError::new_err("resolution must be at least 1x1"));
    }
    Ok((w, h))
}

/// A region as fractions `(x0, x1, y0, y1)` (or `"x0,x1,y0,y1"`), checked
/// as the CLI checks `--crop` and `--mask`.
pub fn fractions(v: &Bound<'_, PyAny>) -> PyResult<[f32; 4]> {
    let c: Vec<f32> = match v.extract::<String>() {
        Ok(s) => s
            .split(',')
            .map(|t| t.trim().parse::<f32>())
            .collect::<Result<_, _>>()
            .map_err(|_| {
                PyValueError::new_err(format!("expected four numbers x0,x1,y0,y1, found `{s}`"))
            })?,
        Err(_) => v.extract()?,
    };
    if c.len() != 4 {
        return Err(PyValueError::new_err(format!(
            "expected four numbers x0,x1,y0,y1, found {}",
            c.len()
        )));
    }
    if c.iter().any(|x| !(0.0..=1.0).contains(x)) || c[0] >= c[1] || c[2] >= c[3] {
        return Err(PyValueError::new_err(
            "the values are fractions in [0,1] with x0 < x1 and y0 < y1",
        ));
    }
    Ok([c[0], c[1], c[2], c[3]])
}
