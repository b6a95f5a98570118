//! A [`CaseFile`] written as case-file TOML: the keys a deck's
//! translation sets (mesh, materials, displacements, pressures, nodal
//! forces, body forces, contacts with their discretisation, steps, output
//! name, every, fields and histories), numbers
//! in Rust's shortest round-trip form, so the text parses back to the same
//! values bit for bit.

use super::super::schema::*;
use std::fmt::Write;
use toml::Value;

/// A number as TOML writes it (round-trips exactly).
fn num(x: f64) -> String {
    Value::Float(x).to_string()
}

fn text(s: &str) -> String {
    Value::String(s.to_string()).to_string()
}

fn triple(v: [f64; 3]) -> String {
    format!("[{}, {}, {}]", num(v[0]), num(v[1]), num(v[2]))
}

fn amplitude(out: &mut String, a: &Option<AmplitudeRef>) {
    match a {
        None => {}
        Some(AmplitudeRef::Named(n)) => {
            let _ = writeln!(out, "amplitude = {}", text(n));
        }
        Some(AmplitudeRef::Points(p)) => {
            let points: Vec<String> = p
                .iter()
                .map(|q| {
                    format!(
                        "[{}]",
                        q.iter().map(|&x| num(x)).collect::<Vec<_>>().join(", ")
                    )
                })
                .collect();
            let _ = writeln!(out, "amplitude = [{}]", points.join(", "));
        }
    }
}

/// `key = value` for the `Some` of an option.
fn opt(out: &mut String, key: &str, v: Option<f64>) {
    if let Some(v) = v {
        let _ = writeln!(out, "{key} = {}", num(v));
    }
}

fn material(out: &mut String, m: &MaterialSpec) {
    let _ = writeln!(out, "\n[[material]]\nregion = {}", text(&m.region));
    let elastic = |out: &mut String, model: &str, c: &ElasticConstants| {
        let _ = writeln!(
            out,
            "model = \"{model}\"\nyoungs_modulus = {}\npoisson_ratio = {}",
            num(c.youngs_modulus),
            num(c.poisson_ratio)
        );
    };
    match &m.model {
        MaterialModel::LinearElastic(c) => elastic(out, "linear_elastic", c),
        MaterialModel::SaintVenantKirchhoff(c) => elastic(out, "saint_venant_kirchhoff", c),
        MaterialModel::NeoHookean(c) => elastic(out, "neo_hookean", c),
        MaterialModel::Ogden(c) => {
            let list = |v: &[f64]| v.iter().map(|&x| num(x)).collect::<Vec<_>>().join(", ");
            let _ = writeln!(
                out,
                "model = \"ogden\"\nmu = [{}]\nalpha = [{}]\nbulk_modulus = {}",
                list(&c.mu),
                list(&c.alpha),
                num(c.bulk_modulus)
            );
        }
    }
}

fn contact(out: &mut String, c: &ContactSpec) {
    let _ = writeln!(out, "\n[[contact]]\nsurface = {}", text(&c.surface));
    for (key, v) in [
        ("name", &c.name),
        ("obstacle", &c.obstacle),
        ("primary", &c.primary),
    ] {
        if let Some(v) = v {
            let _ = writeln!(out, "{key} = {}", text(v));
        }
    }
    let method = match c.method {
        ContactMethod::Penalty => "penalty",
        ContactMethod::Uzawa => "uzawa",
        ContactMethod::Rockafellar => "rockafellar",
        ContactMethod::Slack => "slack",
    };
    let _ = writeln!(out, "method = \"{method}\"");
    // always written: the deck's node-to-surface pairs stay node-to-surface
    // when the case is read back (the case file's default is mortar)
    let discretisation = match c.discretisation {
        Some(DiscretisationSpec::Mortar) => "mortar",
        Some(DiscretisationSpec::NodeToSurface) | None => "node_to_surface",
    };
    let _ = writeln!(out, "discretisation = \"{discretisation}\"");
    opt(out, "penalty", c.penalty);
    opt(out, "scaling", c.scaling);
    opt(out, "friction_coefficient", c.friction_coefficient);
    opt(out, "tangential_penalty", c.tangential_penalty);
    opt(
        out,
        "initial_penetration_tolerance",
        c.initial_penetration_tolerance,
    );
    if let Some(exact) = c.exact_stick {
        let _ = writeln!(out, "exact_stick = {exact}");
    }
    if let Some(m) = c.friction_multiplier {
        let m = match m {
            FrictionMultiplierSpec::Newton => "newton",
            FrictionMultiplierSpec::Outer => "outer",
        };
        let _ = writeln!(out, "friction_multiplier = \"{m}\"");
    }
    if c.two_pass {
        let _ = writeln!(out, "two_pass = true");
    }
}

fn output(out: &mut String, o: &OutputSpec) {
    let _ = writeln!(out, "\n[output]");
    for (key, v) in [("folder", &o.folder), ("name", &o.name)] {
        if let Some(v) = v {
            let _ = writeln!(out, "{key} = {}", text(v));
        }
    }
    if let Some(every) = o.every {
        let _ = writeln!(out, "every = {every}");
    }
    if let Some(fields) = &o.fields {
        let names: Vec<String> = fields.iter().map(|f| text(f.name())).collect();
        let _ = writeln!(out, "fields = [{}]", names.join(", "));
    }
    for h in &o.history {
        let _ = writeln!(
            out,
            "\n[[output.history]]\nname = {}\nquantity = \"{}\"",
            text(&h.name),
            h.quantity.name()
        );
        if let Some(p) = h.point {
            let _ = writeln!(out, "point = {}", triple(p));
        }
        for (key, v) in [
            ("interface", &h.interface),
            ("surface", &h.surface),
            ("nodes", &h.nodes),
        ] {
            if let Some(v) = v {
                let _ = writeln!(out, "{key} = {}", text(v));
            }
        }
    }
}

/// The case file's text of `spec`.
pub fn to_toml(spec: &CaseFile) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "[mesh]\nfile = {}", text(&spec.mesh.file));
    spec.material.iter().for_each(|m| material(&mut out, m));
    for d in &spec.displacement {
        let _ = writeln!(out, "\n[[displacement]]");
        if let Some(s) = &d.surface {
            let _ = writeln!(out, "surface = {}", text(s));
        }
        if let Some(s) = &d.nodes {
            let _ = writeln!(out, "nodes = {}", text(s));
        }
        opt(&mut out, "x", d.x);
        opt(&mut out, "y", d.y);
        opt(&mut out, "z", d.z);
        amplitude(&mut out, &d.amplitude);
    }
    for p in &spec.pressure {
        let _ = writeln!(
            out,
            "\n[[pressure]]\nsurface = {}\nvalue = {}",
            text(&p.surface),
            num(p.value)
        );
        if p.follower {
            let _ = writeln!(out, "follower = true");
        }
        amplitude(&mut out, &p.amplitude);
    }
    for b in &spec.body_force {
        let _ = writeln!(out, "\n[[body_force]]");
        if let Some(r) = &b.region {
            let _ = writeln!(out, "region = {}", text(r));
        }
        let _ = writeln!(out, "value = {}", triple(b.value));
        amplitude(&mut out, &b.amplitude);
    }
    for f in &spec.nodal_force {
        let _ = writeln!(
            out,
            "\n[[nodal_force]]\nnodes = {}\nvalue = {}",
            text(&f.nodes),
            triple(f.value)
        );
        amplitude(&mut out, &f.amplitude);
    }
    spec.contact.iter().for_each(|c| contact(&mut out, c));
    for s in &spec.step {
        let _ = writeln!(
            out,
            "\n[[step]]\nname = {}\nend_time = {}",
            text(&s.name),
            num(s.end_time)
        );
        opt(&mut out, "initial_increment", s.initial_increment);
        opt(&mut out, "min_increment", s.min_increment);
        opt(&mut out, "max_increment", s.max_increment);
    }
    output(&mut out, &spec.output);
    out
}
