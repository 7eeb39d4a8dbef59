//! `builtin_interfaces/msg/Time`: a stamp, nanoseconds since the epoch of its clock, on the
//! wire as whole seconds (`int32 sec`) and the non-negative part below a second
//! (`uint32 nanosec`), as rclcpp writes it: -1.5 s is sec = -2, nanosec = 5e8.

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A stamp in nanoseconds (the node's and the recordings' one time type; with the `ros2`
/// feature it converts to and from `ros2_client`'s).
#[derive(Clone, Copy, Debug, Default, Eq, PartialEq, Ord, PartialOrd, Hash)]
pub struct Time {
    nanos: i64,
}

/// The wire form, field for field, under the message type's name.
#[derive(Serialize, Deserialize)]
#[serde(rename = "Time")]
struct Wire {
    sec: i32,
    nanosec: u32,
}

const NS_PER_S: i64 = 1_000_000_000;

impl Time {
    /// The epoch itself, 0 ns.
    pub const ZERO: Time = Time { nanos: 0 };

    /// The stamp `nanos` ns after the epoch.
    pub const fn from_nanos(nanos: i64) -> Self {
        Self { nanos }
    }

    /// Nanoseconds since the epoch.
    pub const fn to_nanos(self) -> i64 {
        self.nanos
    }

    /// From the wire's fields; a `nanosec` of a second or more folds into the seconds.
    pub(crate) const fn new(sec: i32, nanosec: u32) -> Self {
        Self::from_nanos(sec as i64 * NS_PER_S + nanosec as i64)
    }

    /// The wire's fields: seconds rounded down, saturated to `int32` (past 2038 a stamp stops
    /// at `i32::MAX` s, as ros2-client's conversion does), and the remainder in [0, 1e9) ns.
    pub(crate) const fn sec_nanosec(self) -> (i32, u32) {
        let sec = self.nanos.div_euclid(NS_PER_S);
        let nanosec = self.nanos.rem_euclid(NS_PER_S) as u32;
        if sec > i32::MAX as i64 {
            (i32::MAX, nanosec)
        } else if sec < i32::MIN as i64 {
            (i32::MIN, nanosec)
        } else {
            (sec as i32, nanosec)
        }
    }
}

impl Serialize for Time {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let (sec, nanosec) = self.sec_nanosec();
        Wire { sec, nanosec }.serialize(s)
    }
}

impl<'de> Deserialize<'de> for Time {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let w = Wire::deserialize(d)?;
        Ok(Time::new(w.sec, w.nanosec))
    }
}

#[cfg(feature = "ros2")]
impl From<Time> for ros2_client::builtin_interfaces::Time {
    fn from(t: Time) -> Self {
        Self::from_nanos(t.nanos)
    }
}

#[cfg(feature = "ros2")]
impl From<ros2_client::builtin_interfaces::Time> for Time {
    fn from(t: ros2_client::builtin_interfaces::Time) -> Self {
        Self::from_nanos(t.to_nanos())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wire_fields_round_down_with_a_non_negative_remainder() {
        assert_eq!(Time::from_nanos(0).sec_nanosec(), (0, 0));
        assert_eq!(
            Time::from_nanos(1_500_000_000).sec_nanosec(),
            (1, 500_000_000)
        );
        assert_eq!(
            Time::from_nanos(-1_500_000_000).sec_nanosec(),
            (-2, 500_000_000)
        );
        assert_eq!(Time::from_nanos(-1).sec_nanosec(), (-1, 999_999_999));
        assert_eq!(Time::from_nanos(-1_000_000_000).sec_nanosec(), (-1, 0));
        assert_eq!(Time::from_nanos(i64::MAX).sec_nanosec().0, i32::MAX);
        for ns in [
            0,
            1,
            -1,
            999_999_999,
            -999_999_999,
            1_234_567_890_123,
            -7_000_000_001,
        ] {
            let (s, n) = Time::from_nanos(ns).sec_nanosec();
            assert_eq!(Time::new(s, n).to_nanos(), ns);
        }
        assert_eq!(Time::new(1, 1_500_000_000).to_nanos(), 2_500_000_000);
    }

    /// The same bytes as `ros2_client`'s own type, whose wire form the node's peers read.
    #[cfg(feature = "ros2")]
    #[test]
    fn serializes_as_ros2_clients_time() {
        for ns in [0, 1, -1, 1_234_567_890_123, -7_000_000_001, 1 << 62] {
            let ours = cdr_encoding::to_vec::<_, byteorder::LittleEndian>(&Time::from_nanos(ns));
            let theirs = cdr_encoding::to_vec::<_, byteorder::LittleEndian>(
                &ros2_client::builtin_interfaces::Time::from_nanos(ns),
            );
            assert_eq!(ours.unwrap(), theirs.unwrap(), "{ns} ns");
        }
    }
}
