//! The physics keywords of a deck and their data lines, read into
//! [`Physics`](super::physics::Physics) records: materials, sections,
//! amplitudes, time points, surface interactions, contact pairs, steps
//! with their boundary conditions, loads and output requests. Names are
//! resolved against the sets read so far (qualified by instance); node ids
//! become implicit node sets `node:<id>`, `*DLOAD` faces implicit surfaces
//! `<elset>:S<k>`. A keyword that changes the answer and is not read is an
//! error that names it; those that do not are listed in
//! `Physics::without_effect`.

use super::deck::{unquote, Keyword, Line};
use super::physics::*;
use super::{data_fields, Member, Mode, Reader};
use crate::Result;

/// Keywords that do not change the answer of a static run with isotropic
/// materials: printed and restart output, solver controls, thermal constants (no temperature is
/// read), orientations (the materials are isotropic).
const WITHOUT_EFFECT: &[&str] = &[
    "PREPRINT",
    "OUTPUT",
    "RESTART",
    "EL PRINT",
    "CONTACT PRINT",
    "ENERGY PRINT",
    "SECTION PRINT",
    "CONTROLS",
    "CONTACT CONTROLS",
    "DIAGNOSTICS",
    "MONITOR",
    "FILE FORMAT",
    "EXPANSION",
    "CONDUCTIVITY",
    "SPECIFIC HEAT",
    "ORIENTATION",
    "PHYSICAL CONSTANTS",
    "CONTACT OUTPUT",
];

impl Reader<'_> {
    /// A keyword other than the mesh's. Reading for the mesh only, it is
    /// listed as ignored and its errors are dropped (its implicit sets
    /// stay, so that the mesh is the one the deck's run reads).
    pub(super) fn physics_keyword(
        &mut self,
        line: &Line,
        keyword: &Keyword,
        data: &[Line],
    ) -> Result<()> {
        let result = self.physics(line, keyword, data);
        match self.mode {
            Mode::Deck => result,
            Mode::Mesh => {
                let name = format!("*{}", keyword.name);
                if !self.ignored.contains(&name) {
                    self.ignored.push(name);
                }
                Ok(())
            }
        }
    }

    fn physics(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let name = keyword.name.as_str();
        match name {
            "MATERIAL" => self.material(line, keyword),
            "ELASTIC" => self.elastic(line, keyword, data),
            "HYPERELASTIC" => self.hyperelastic(line, keyword, data),
            "DENSITY" => self.density(line, keyword, data),
            "SOLID SECTION" => self.solid_section(line, keyword),
            "AMPLITUDE" => self.amplitude(line, keyword, data),
            "TIME POINTS" => self.time_points(line, keyword, data),
            "SURFACE INTERACTION" => self.surface_interaction(line, keyword),
            "SURFACE BEHAVIOR" => self.surface_behavior(line, keyword, data),
            "FRICTION" => self.friction(line, keyword, data),
            "CONTACT PAIR" => self.contact_pair(line, keyword, data),
            "STEP" => self.step(line, keyword),
            "STATIC" => self.static_step(line, keyword, data),
            "END STEP" => self.end_step(line),
            "BOUNDARY" => self.boundary(line, keyword, data),
            "CLOAD" => self.cload(line, keyword, data),
            "DLOAD" | "DSLOAD" => self.pressure(line, keyword, data),
            "NODE FILE" | "NODE OUTPUT" | "EL FILE" | "ELEMENT OUTPUT" | "CONTACT FILE"
            | "NODE PRINT" => self.output(line, keyword, data),
            _ if WITHOUT_EFFECT.contains(&name) => {
                self.without_effect(name);
                Ok(())
            }
            _ => Err(self.err(
                line,
                format!(
                    "*{name} is not supported: it changes the model, and running the deck without it \
                     would give another answer; remove it, or write the case in TOML (signorini \
                     convert gives one to start from) and model it there"
                ),
            )),
        }
    }

    fn without_effect(&mut self, name: &str) {
        let name = format!("*{name}");
        if !self.physics.without_effect.contains(&name) {
            self.physics.without_effect.push(name);
        }
    }

    /// An error for a parameter that changes the answer and is not read.
    pub(super) fn refuse(&self, line: &Line, keyword: &Keyword, params: &[&str]) -> Result<()> {
        match params.iter().find(|p| keyword.has(p)) {
            Some(p) => Err(self.err(
                line,
                format!(
                    "*{}, {p} is not supported (it changes the answer)",
                    keyword.name
                ),
            )),
            None => Ok(()),
        }
    }

    /// The numbers of the data lines, all fields in order.
    fn numbers(&self, data: &[Line]) -> Result<Vec<f64>> {
        let mut out = Vec::new();
        for l in data {
            for f in data_fields(l) {
                out.push(self.number(l, f)?);
            }
        }
        Ok(out)
    }

    /// Exactly one data line of `n` numbers (missing trailing ones are 0).
    pub(super) fn one_line(
        &self,
        line: &Line,
        keyword: &Keyword,
        data: &[Line],
        n: usize,
    ) -> Result<Vec<f64>> {
        if data.len() != 1 {
            return Err(self.err(
                line,
                format!(
                    "*{} takes one data line here (found {}); temperature-dependent tables are not supported",
                    keyword.name,
                    data.len()
                ),
            ));
        }
        let mut v = self.numbers(data)?;
        if v.len() > n {
            return Err(self.err(
                &data[0],
                format!(
                    "*{} takes {n} numbers here; found {}",
                    keyword.name,
                    v.len()
                ),
            ));
        }
        v.resize(n, 0.0);
        Ok(v)
    }

    fn material(&mut self, line: &Line, keyword: &Keyword) -> Result<()> {
        let name = self.required(line, keyword, "NAME")?.to_string();
        if self
            .physics
            .materials
            .iter()
            .any(|m| m.name.eq_ignore_ascii_case(&name))
        {
            return Err(self.err(line, format!("*MATERIAL '{name}' is defined twice")));
        }
        self.physics.materials.push(MaterialDef {
            name,
            elastic: None,
            hyperelastic: None,
            density: None,
            at: self.deck.locate(line),
        });
        self.material = Some(self.physics.materials.len() - 1);
        Ok(())
    }

    /// The material that `*ELASTIC` or `*HYPERELASTIC` at `line` describes.
    fn current_material(&self, line: &Line, keyword: &Keyword) -> Result<usize> {
        self.material
            .ok_or_else(|| self.err(line, format!("*{} before any *MATERIAL", keyword.name)))
    }

    /// `*ELASTIC[, TYPE=ISOTROPIC]`: `E, ν`.
    fn elastic(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let m = self.current_material(line, keyword)?;
        if let Some(t) = keyword.param("TYPE") {
            if !t.eq_ignore_ascii_case("ISO") && !t.eq_ignore_ascii_case("ISOTROPIC") {
                return Err(self.err(
                    line,
                    format!(
                        "*ELASTIC, TYPE={t} is not supported: only isotropic elasticity (E, ν) is"
                    ),
                ));
            }
        }
        let v = self.one_line(line, keyword, data, 2)?;
        self.physics.materials[m].elastic = Some((v[0], v[1]));
        Ok(())
    }

    /// `*DENSITY`: `ρ` (mass per unit volume; a temperature after it is
    /// not read).
    fn density(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let m = self.current_material(line, keyword)?;
        let v = self.one_line(line, keyword, data, 2)?;
        self.physics.materials[m].density = Some(v[0]);
        Ok(())
    }

    /// `*HYPERELASTIC, NEO HOOKE` (`C10, D1`) or `*HYPERELASTIC, OGDEN,
    /// N=n` (`μ1, α1, …, μn, αn, D1, …, Dn`, n ≤ 3).
    fn hyperelastic(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let m = self.current_material(line, keyword)?;
        let model = if keyword.has("NEO HOOKE") {
            let v = self.one_line(line, keyword, data, 2)?;
            Hyperelastic::NeoHooke {
                c10: v[0],
                d1: v[1],
            }
        } else if keyword.has("OGDEN") {
            let n = match keyword.param("N") {
                None => 1,
                Some(n) => n
                    .parse::<usize>()
                    .ok()
                    .filter(|n| (1..=3).contains(n))
                    .ok_or_else(|| {
                        self.err(line, format!("*HYPERELASTIC, OGDEN, N={n}: N is 1, 2 or 3"))
                    })?,
            };
            let v = self.numbers(data)?;
            if v.len() != 3 * n {
                return Err(self.err(
                    line,
                    format!("*HYPERELASTIC, OGDEN, N={n} takes {} numbers (μ_i, α_i, then D_i); found {}", 3 * n, v.len()),
                ));
            }
            Hyperelastic::Ogden {
                mu: (0..n).map(|i| v[2 * i]).collect(),
                alpha: (0..n).map(|i| v[2 * i + 1]).collect(),
                d: v[2 * n..].to_vec(),
            }
        } else {
            return Err(self.err(
                line,
                "*HYPERELASTIC: only NEO HOOKE and OGDEN (N = 1 to 3) are supported".into(),
            ));
        };
        self.physics.materials[m].hyperelastic = Some(model);
        Ok(())
    }

    /// `*SOLID SECTION, ELSET=…, MATERIAL=…`.
    fn solid_section(&mut self, line: &Line, keyword: &Keyword) -> Result<()> {
        let elset = self.context.name(self.required(line, keyword, "ELSET")?);
        let material = self.required(line, keyword, "MATERIAL")?.to_string();
        let members = self.builder.element_sets.get(&elset).ok_or_else(|| {
            self.err(
                line,
                format!(
                    "*SOLID SECTION: {}",
                    self.missing_set(&elset, "element set")
                ),
            )
        })?;
        if !members.iter().any(|m| matches!(m, Member::Volume(_))) {
            return Err(self.err(
                line,
                format!("*SOLID SECTION: element set '{elset}' holds no C3D4 or C3D8 element"),
            ));
        }
        let region = self
            .builder
            .element_sets
            .canonical(&elset)
            .unwrap_or(&elset)
            .to_string();
        self.physics.sections.push(SectionDef {
            region,
            material,
            at: self.deck.locate(line),
        });
        Ok(())
    }

    /// `*AMPLITUDE, NAME=…[, TIME=TOTAL TIME]`: `t1, a1, t2, a2, …`.
    fn amplitude(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let name = self.required(line, keyword, "NAME")?.to_string();
        self.refuse(line, keyword, &["SHIFTX", "SHIFTY", "USER"])?;
        if let Some(d) = keyword.param("DEFINITION") {
            if !d.eq_ignore_ascii_case("TABULAR") {
                return Err(self.err(line, format!("*AMPLITUDE, DEFINITION={d} is not supported: give a table (t, a) of points")));
            }
        }
        let total_time = keyword
            .param("TIME")
            .is_some_and(|t| t.eq_ignore_ascii_case("TOTAL TIME"));
        let v = self.numbers(data)?;
        if v.is_empty() || v.len() % 2 != 0 {
            return Err(self.err(
                line,
                format!(
                    "*AMPLITUDE '{name}': pairs 'time, value' are expected; found {} numbers",
                    v.len()
                ),
            ));
        }
        let points: Vec<(f64, f64)> = v.chunks(2).map(|p| (p[0], p[1])).collect();
        if points.windows(2).any(|w| !(w[1].0 > w[0].0)) {
            return Err(self.err(
                line,
                format!("*AMPLITUDE '{name}': the times must increase"),
            ));
        }
        self.physics.amplitudes.push(AmplitudeDef {
            name,
            points,
            total_time,
            at: self.deck.locate(line),
        });
        Ok(())
    }

    /// `*TIME POINTS, NAME=…[, GENERATE]`: times, or `start, end, step`.
    fn time_points(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let name = self.required(line, keyword, "NAME")?.to_string();
        if keyword
            .param("TIME")
            .is_some_and(|t| t.eq_ignore_ascii_case("TOTAL TIME"))
        {
            return Err(self.err(
                line,
                "*TIME POINTS, TIME=TOTAL TIME is not supported: give step times".into(),
            ));
        }
        let v = self.numbers(data)?;
        let times = if keyword.has("GENERATE") {
            if v.len() % 3 != 0 || v.is_empty() {
                return Err(self.err(
                    line,
                    "*TIME POINTS, GENERATE takes lines 'start, end, increment'".into(),
                ));
            }
            let mut t = Vec::new();
            for g in v.chunks(3) {
                if !(g[2] > 0.0) || (g[1] - g[0]) / g[2] > 1e6 {
                    return Err(self.err(line, "*TIME POINTS, GENERATE: the increment must be positive and give at most 10⁶ points".into()));
                }
                let n = ((g[1] - g[0]) / g[2] + 1e-9).floor() as usize;
                t.extend((0..=n).map(|k| g[0] + k as f64 * g[2]));
            }
            t
        } else {
            v
        };
        self.physics.time_points.push((name, times));
        Ok(())
    }

    fn surface_interaction(&mut self, line: &Line, keyword: &Keyword) -> Result<()> {
        let name = self.required(line, keyword, "NAME")?.to_string();
        self.physics.interactions.push(InteractionDef {
            name,
            overclosure: Overclosure::Hard,
            friction: None,
            at: self.deck.locate(line),
        });
        self.interaction = Some(self.physics.interactions.len() - 1);
        Ok(())
    }

    fn current_interaction(&self, line: &Line, keyword: &Keyword) -> Result<usize> {
        self.interaction.ok_or_else(|| {
            self.err(
                line,
                format!("*{} before any *SURFACE INTERACTION", keyword.name),
            )
        })
    }

    /// `*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD` or `=LINEAR` (data
    /// line: the slope, pressure per overclosure).
    fn surface_behavior(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let i = self.current_interaction(line, keyword)?;
        let law = keyword.param("PRESSURE-OVERCLOSURE").unwrap_or("HARD");
        let overclosure = if law.eq_ignore_ascii_case("HARD") {
            Overclosure::Hard
        } else if law.eq_ignore_ascii_case("LINEAR") {
            let v = self.numbers(data)?;
            match v.first() {
                Some(&slope) if slope > 0.0 => Overclosure::Linear { slope },
                _ => {
                    return Err(self.err(
                        line,
                        "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR needs a data line with the slope (> 0, pressure per overclosure)".into(),
                    ))
                }
            }
        } else {
            return Err(self.err(
                line,
                format!("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE={law} is not supported: HARD (exact contact) or LINEAR (penalty) are"),
            ));
        };
        self.physics.interactions[i].overclosure = overclosure;
        Ok(())
    }

    /// `*FRICTION[, LAGRANGE | EXACT][, SLIP TOLERANCE=…]`: `μ[, stick slope]`.
    fn friction(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let i = self.current_interaction(line, keyword)?;
        self.refuse(
            line,
            keyword,
            &[
                "ROUGH",
                "ELASTIC SLIP",
                "TAUMAX",
                "EXPONENTIAL DECAY",
                "ANISOTROPIC",
                "USER",
                "DEPENDENCIES",
            ],
        )?;
        let v = self.one_line(line, keyword, data, 2)?;
        let slip_tolerance = match keyword.param("SLIP TOLERANCE") {
            None => None,
            Some(s) => Some(self.number(line, s)?),
        };
        self.physics.interactions[i].friction = Some(FrictionDef {
            mu: v[0],
            stick_slope: (v[1] != 0.0).then_some(v[1]),
            exact: keyword.has("LAGRANGE") || keyword.has("EXACT"),
            slip_tolerance,
        });
        Ok(())
    }

    /// A surface name as the mesh has it (its first spelling).
    pub(super) fn surface_name(&self, l: &Line, raw: &str, what: &str) -> Result<String> {
        let name = self.context.name(unquote(raw));
        self.builder
            .surfaces
            .canonical(&name)
            .map(str::to_string)
            .ok_or_else(|| {
                self.err(
                    l,
                    format!("{what}: {}", self.missing_set(&name, "*SURFACE")),
                )
            })
    }

    /// `*CONTACT PAIR, INTERACTION=…[, TYPE=…]`: lines `secondary, primary`.
    fn contact_pair(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let interaction = self.required(line, keyword, "INTERACTION")?.to_string();
        let pair_type = match keyword.param("TYPE") {
            None => PairType::Unspecified,
            Some(t) => PairType::parse(t).map_err(|m| self.err(line, m))?,
        };
        self.refuse(line, keyword, &["TIED", "HCRIT", "EXTENSION ZONE"])?;
        if let Some(adjust) = keyword.param("ADJUST") {
            if !adjust.parse::<f64>().is_ok_and(|a| a == 0.0) {
                return Err(self.err(line, format!("*CONTACT PAIR, ADJUST={adjust} is not supported: it moves the secondary nodes onto the primary surface; mesh them there")));
            }
        }
        if data.is_empty() {
            return Err(self.err(
                line,
                "*CONTACT PAIR has no data line 'secondary surface, primary surface'".into(),
            ));
        }
        for l in data {
            let f = data_fields(l);
            if f.len() != 2 {
                return Err(self.err(
                    l,
                    format!(
                        "a *CONTACT PAIR line is 'secondary surface, primary surface'; found '{}'",
                        l.text()
                    ),
                ));
            }
            let secondary = self.surface_name(l, f[0], "*CONTACT PAIR secondary surface")?;
            let primary = self.surface_name(l, f[1], "*CONTACT PAIR primary surface")?;
            self.physics.contact_pairs.push(ContactPairDef {
                interaction: interaction.clone(),
                pair_type: pair_type.clone(),
                secondary,
                primary,
                at: self.deck.locate(l),
            });
        }
        Ok(())
    }
}
