//! The figures' colours: each model's by its place in [`MODELS`](muscle_actuator_core::physics::models::MODELS),
//! and the named ones the figures share.

use muscle_actuator_core::physics::models::ModelKind;
use plotters::style::RGBColor;

/// Red, the first model's.
pub const RED: RGBColor = RGBColor(0xd6, 0x27, 0x28);
/// Blue, the second model's.
pub const BLUE: RGBColor = RGBColor(0x1f, 0x77, 0xb4);
/// Green, the third model's.
pub const GREEN: RGBColor = RGBColor(0x2c, 0xa0, 0x2c);
/// Black, for reference lines and published points.
pub const BLACK: RGBColor = RGBColor(0x00, 0x00, 0x00);
/// Orange, a second curve of one model.
pub const ORANGE: RGBColor = RGBColor(0xff, 0x7f, 0x0e);

/// The models' colours, by their position in [`MODELS`](muscle_actuator_core::physics::models::MODELS)
/// (repeating after the sixth).
const PALETTE: [RGBColor; 6] = [
    RED,
    BLUE,
    GREEN,
    RGBColor(0x94, 0x67, 0xbd),
    ORANGE,
    RGBColor(0x8c, 0x56, 0x4b),
];

/// A model's colour: its position in the model list.
pub fn color(model: ModelKind) -> RGBColor {
    let i = ModelKind::all().position(|m| m == model).unwrap_or(0);
    PALETTE[i % PALETTE.len()]
}
