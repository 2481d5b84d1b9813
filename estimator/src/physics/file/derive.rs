//! A model file's reported values: its parameters and `[derived]` values, SI where the data
//! determine them, where reference frames calibrated the map, or where bodies' known positions
//! give the latent's scale; latent units otherwise.

use super::FileModel;
use crate::calibration::{
    needs_reference, position_scale, Calibration, DerivedValue, Readings, POSITION_FIT_R2,
};
use crate::physics::Derived;
use physvid_shared::model_file::symmetry::{transformed, Transform};

impl FileModel {
    /// The parameters in the units of the bodies' known positions at reference frames, for a
    /// latent of (x, y) pairs whose law no common shift changes (see [`FileModel::derive`]).
    fn scaled_by_positions(
        &self,
        p: &[f64],
        cal: &Calibration,
        readings: &Readings,
        warnings: &mut Vec<String>,
    ) -> Option<Vec<f64>> {
        let d = self.file.observed.len();
        let shift_free = self
            .symmetries
            .shift
            .as_ref()
            .is_some_and(|s| !s.contains(&true));
        if d < 2 || !d.is_multiple_of(2) || !shift_free || self.symmetries.scale.is_none() {
            return None;
        }
        let (scale, r2) = position_scale(cal, &readings.positions)?;
        if r2 < POSITION_FIT_R2 {
            warnings.push(format!(
                "the reference frames' positions fit the latent only with R² {r2:.3} (a \
                 similarity should fit exactly): the values converted with its scale are suspect"
            ));
        }
        transformed(
            &self.file,
            &self.system.compiled,
            p,
            Transform::Scale(1.0 / scale),
        )
    }
}

impl FileModel {
    /// The file's parameters, and values derived from them: SI where the data determine them,
    /// where reference frames calibrated the map, or where bodies' known positions give the
    /// latent's scale (a vector latent of (x, y) pairs, a law that no shift of the positions
    /// changes: the parameters are then rescaled as the law demands); latent units otherwise.
    pub(super) fn values(&self, params: &[f64], cal: &Calibration, readings: &Readings) -> Derived {
        let m = self.file.parameters.len();
        let mut warnings = Vec::new();
        let scaled = self.scaled_by_positions(&params[..m], cal, readings, &mut warnings);
        let calibrated = self.calibrated(cal) || scaled.is_some();
        let params: Vec<f64> = scaled
            .unwrap_or_else(|| params[..m].to_vec())
            .into_iter()
            .chain(params[m..].iter().copied())
            .collect();
        let latent = |j: usize| !calibrated && self.symmetries.latent_units(j);
        let mut values = Vec::new();
        let mut in_latent = Vec::new();
        for (j, p) in self.file.parameters.iter().enumerate() {
            if latent(j) {
                in_latent.push(p.name.clone());
                values.push(DerivedValue::latent(&p.name, params[j]));
            } else {
                values.push(DerivedValue::si(
                    &p.name,
                    self.units[j],
                    params[j],
                    Some(self.info.law.truth[j].name),
                ));
            }
        }
        let n = self.file.states.len();
        for (k, (d, v)) in self
            .file
            .derived
            .iter()
            .zip(self.file.derived_values(&params[..m]))
            .enumerate()
        {
            if (0..m).any(|j| latent(j) && d.expr.uses(n + j)) {
                values.push(DerivedValue::latent(&d.name, v));
            } else {
                values.push(DerivedValue::si(
                    &d.name,
                    self.units[m + k],
                    v,
                    Some(self.info.law.truth[m + k].name),
                ));
            }
        }
        for (spec, v) in self.info.law.parameters[m..].iter().zip(&params[m..]) {
            values.push(DerivedValue::latent(spec.name, *v));
        }
        if !in_latent.is_empty() {
            warnings.push(needs_reference(&in_latent.join(", ")));
        }
        (values, warnings)
    }
}
