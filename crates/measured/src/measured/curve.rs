//! A curve of CEINMS's subject file, as points: x strictly increasing, as many y as x, all
//! finite. CEINMS interpolates them with cubic splines (Forsythe, Malcolm & Moler 1977, in the
//! toolbox's lib/Curve/Curve.cpp) and holds the end values outside them; here they are points
//! only.

/// A curve's points `(x[i], y[i])`, x strictly increasing, at least two, all finite.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    x: Vec<f64>,
    y: Vec<f64>,
}

impl Curve {
    /// The curve through `(x[i], y[i])`: as many y as x, at least two points, all finite, x
    /// strictly increasing.
    pub fn new(x: Vec<f64>, y: Vec<f64>) -> Result<Curve, CurveError> {
        if x.len() != y.len() {
            return Err(CurveError::Lengths {
                x: x.len(),
                y: y.len(),
            });
        }
        if x.len() < 2 {
            return Err(CurveError::TooFewPoints { points: x.len() });
        }
        if let Some(index) = x.iter().chain(&y).position(|v| !v.is_finite()) {
            return Err(CurveError::NotFinite { index });
        }
        if let Some(i) = (1..x.len()).find(|&i| x[i] <= x[i - 1]) {
            return Err(CurveError::NotIncreasing {
                index: i,
                x: x[i],
                previous: x[i - 1],
            });
        }
        Ok(Curve { x, y })
    }

    /// The abscissae, strictly increasing.
    pub fn x(&self) -> &[f64] {
        &self.x
    }

    /// The ordinates, one per abscissa.
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    /// The points as `[x, y]` pairs, in order (a tabulated curve's form).
    pub fn points(&self) -> Vec<[f64; 2]> {
        self.x.iter().zip(&self.y).map(|(&x, &y)| [x, y]).collect()
    }

    /// The number of points (two or more).
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// Always false: a curve has at least two points.
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }
}

/// Why points do not make a curve; indices count from 0.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CurveError {
    /// Another count of y than of x.
    #[error("{x} x points and {y} y points")]
    Lengths {
        /// The x count.
        x: usize,
        /// The y count.
        y: usize,
    },
    /// Fewer than two points.
    #[error("{points} point(s), a curve has at least two")]
    TooFewPoints {
        /// The count.
        points: usize,
    },
    /// A value that is not finite (only for points not read from text, which refuses them).
    #[error("value {index} (x then y) is not finite")]
    NotFinite {
        /// Its index among the x, then the y.
        index: usize,
    },
    /// An x not above the one before.
    #[error("x[{index}] = {x} is not above x[{}] = {previous}", .index - 1)]
    NotIncreasing {
        /// Its index.
        index: usize,
        /// Its value.
        x: f64,
        /// The one before.
        previous: f64,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_curve_needs_equal_lengths_two_points_and_increasing_x() {
        let c = Curve::new(vec![0.0, 1.0, 2.0], vec![0.0, 1.0, 0.5]).unwrap();
        assert_eq!(
            (c.x(), c.y(), c.len(), c.is_empty()),
            (&[0.0, 1.0, 2.0][..], &[0.0, 1.0, 0.5][..], 3, false)
        );
        assert_eq!(
            Curve::new(vec![0.0, 1.0], vec![0.0]).unwrap_err(),
            CurveError::Lengths { x: 2, y: 1 }
        );
        assert_eq!(
            Curve::new(vec![0.0], vec![0.0]).unwrap_err(),
            CurveError::TooFewPoints { points: 1 }
        );
        let e = Curve::new(vec![0.0, 1.0, 1.0], vec![0.0; 3]).unwrap_err();
        assert_eq!(e.to_string(), "x[2] = 1 is not above x[1] = 1");
        assert_eq!(
            Curve::new(vec![0.0, 1.0], vec![0.0, f64::NAN]).unwrap_err(),
            CurveError::NotFinite { index: 3 }
        );
    }
}
