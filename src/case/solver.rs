//! The `[solver]` table: Newton's and the stepping's controls, with the
//! defaults of [`SolverSettings::default`], validated.

use super::Case;
use crate::problem::{LinearMethod, SolverSettings};
use crate::Result;

impl Case {
    /// `[solver]` over the defaults, validated ([`Self::check_settings`]).
    pub(super) fn settings(&self) -> Result<SolverSettings> {
        let spec = &self.spec;
        let d = SolverSettings::default();
        let sv = &spec.solver;
        let settings = SolverSettings {
            max_iterations: sv.max_iterations.unwrap_or(d.max_iterations),
            residual_tolerance: sv.residual_tolerance.unwrap_or(d.residual_tolerance),
            displacement_tolerance: sv
                .displacement_tolerance
                .unwrap_or(d.displacement_tolerance),
            line_search: sv.line_search.unwrap_or(d.line_search),
            max_cuts: sv.max_cuts.unwrap_or(d.max_cuts),
            growth_factor: sv.growth_factor.unwrap_or(d.growth_factor),
            easy_iterations: sv.easy_iterations.unwrap_or(d.easy_iterations),
            nonsymmetric: sv.nonsymmetric.unwrap_or(d.nonsymmetric),
            linear: sv.linear.unwrap_or(d.linear),
            predictor: sv.predictor.unwrap_or(d.predictor),
            strategy: sv.strategy.unwrap_or(d.strategy),
            petsc_options: sv
                .petsc
                .as_ref()
                .and_then(|p| p.options.clone())
                .unwrap_or_default(),
        };
        self.check_settings(&settings)?;
        Ok(settings)
    }

    /// The PETSc backend named where it is built, the tolerances in
    /// `(0, 1)`, the growth factor a finite number ≥ 1, and at least one
    /// Newton iteration.
    fn check_settings(&self, settings: &SolverSettings) -> Result<()> {
        let sv = &self.spec.solver;
        if sv.petsc.is_some() && settings.linear != LinearMethod::Petsc {
            return Err(self.err(
                "[solver.petsc] is set but solver.linear is not \"petsc\": \
                 add linear = \"petsc\" or remove [solver.petsc]"
                    .to_string(),
            ));
        }
        if settings.linear == LinearMethod::Petsc && !cfg!(feature = "petsc") {
            return Err(self.err(crate::solve::backend::PETSC_MISSING.to_string()));
        }
        for (name, v) in [
            ("residual_tolerance", settings.residual_tolerance),
            ("displacement_tolerance", settings.displacement_tolerance),
        ] {
            if !(v > 0.0 && v < 1.0) {
                return Err(self.err(format!("solver.{name} = {v} must be in (0, 1)")));
            }
        }
        if !settings.growth_factor.is_finite() {
            return Err(self.err(format!(
                "solver.growth_factor = {} is not a finite number; give a value ≥ 1 (default 1.5)",
                settings.growth_factor
            )));
        }
        if !(settings.growth_factor >= 1.0) {
            return Err(self.err(format!(
                "solver.growth_factor = {} must be ≥ 1",
                settings.growth_factor
            )));
        }
        if settings.max_iterations == 0 {
            return Err(self.err("solver.max_iterations must be at least 1"));
        }
        Ok(())
    }
}
