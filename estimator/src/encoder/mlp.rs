//! The MLP encoders (small, the paper's, linear): flattened frame → latent numbers.

use tch::nn;

/// An MLP with ReLU between layers and Kaiming-uniform (fan-in, ReLU gain) weights, tch's
/// default: `inputs` pixels through `hidden` widths to `dims` numbers.
pub fn mlp(path: &nn::Path, inputs: i64, hidden: &[i64], dims: i64) -> nn::Sequential {
    let mut seq = nn::seq();
    let mut width = inputs;
    for (i, &h) in hidden.iter().enumerate() {
        seq = seq
            .add(nn::linear(
                path / format!("fc{i}"),
                width,
                h,
                Default::default(),
            ))
            .add_fn(|x| x.relu());
        width = h;
    }
    seq.add(nn::linear(path / "out", width, dims, Default::default()))
}
