//! The edges of the scan: where the %I area comes from and where the %Q
//! area goes. Real fieldbus and simulation drivers implement these traits;
//! the runtime itself only copies areas.

/// Fills the %I area before the tasks of a scan run.
pub trait InputSource {
    fn read(&mut self, plc_time_ns: i64, input: &mut [u8]);
}

/// Receives the %Q area after the tasks of a scan ran (and once more, all
/// zero, when the PLC stops in its fault state).
pub trait OutputSink {
    fn write(&mut self, plc_time_ns: i64, output: &[u8]);
}

/// No inputs (the %I area keeps what the program or forcing put there) and
/// no outputs.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoIo;

impl InputSource for NoIo {
    fn read(&mut self, _plc_time_ns: i64, _input: &mut [u8]) {}
}

impl OutputSink for NoIo {
    fn write(&mut self, _plc_time_ns: i64, _output: &[u8]) {}
}

/// One forced input: a whole byte range, or one bit of a byte, relative to
/// the start of the %I area.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Force {
    Bytes { offset: usize, bytes: Vec<u8> },
    Bit { offset: usize, bit: u8, value: bool },
}

/// An input source that writes forced values into the %I area every scan
/// (the other bytes keep their values). Forces outside the area are
/// ignored: the area size comes from the program, the forces from the user.
#[derive(Clone, Debug, Default)]
pub struct ForcedInputs {
    pub forces: Vec<Force>,
}

impl InputSource for ForcedInputs {
    fn read(&mut self, _plc_time_ns: i64, input: &mut [u8]) {
        for f in &self.forces {
            match f {
                Force::Bytes { offset, bytes } => {
                    let end = offset.saturating_add(bytes.len());
                    if let Some(dst) = input.get_mut(*offset..end) {
                        dst.copy_from_slice(bytes);
                    }
                }
                Force::Bit { offset, bit, value } => {
                    if let (Some(b), true) = (input.get_mut(*offset), *bit < 8) {
                        if *value {
                            *b |= 1 << bit;
                        } else {
                            *b &= !(1 << bit);
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forces_bytes_and_bits_inside_the_area_only() {
        let mut src = ForcedInputs {
            forces: vec![
                Force::Bytes {
                    offset: 1,
                    bytes: vec![0xAA, 0xBB],
                },
                Force::Bit {
                    offset: 0,
                    bit: 3,
                    value: true,
                },
                Force::Bit {
                    offset: 3,
                    bit: 0,
                    value: false,
                },
                Force::Bytes {
                    offset: 3,
                    bytes: vec![1, 2],
                },
                Force::Bit {
                    offset: 9,
                    bit: 1,
                    value: true,
                },
            ],
        };
        let mut area = [0x01, 0, 0, 0xFF];
        src.read(0, &mut area);
        assert_eq!(area, [0x09, 0xAA, 0xBB, 0xFE]);
    }
}
