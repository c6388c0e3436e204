//! The serial line of Modbus RTU: its settings and opening the port with
//! the `serialport` crate (termios on Unix; a pseudo-terminal such as
//! socat's works like a UART).

use crate::rtu;
use std::time::Duration;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Parity {
    None,
    Even,
    Odd,
}

impl Parity {
    pub fn parse(s: &str) -> Option<Parity> {
        Some(match s {
            "none" | "N" => Parity::None,
            "even" | "E" => Parity::Even,
            "odd" | "O" => Parity::Odd,
            _ => return None,
        })
    }
    pub fn name(self) -> &'static str {
        match self {
            Parity::None => "none",
            Parity::Even => "even",
            Parity::Odd => "odd",
        }
    }
}

/// A serial line: 8 data bits always (RTU has no other).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Line {
    pub device: String,
    pub baud: u32,
    pub parity: Parity,
    pub stop_bits: u8,
}

impl Line {
    /// The specification's default: 19200 baud, even parity, 1 stop bit.
    pub fn new(device: &str) -> Line {
        Line {
            device: device.to_string(),
            baud: 19_200,
            parity: Parity::Even,
            stop_bits: 1,
        }
    }

    /// The silence that ends a frame on this line.
    pub fn gap(&self) -> Duration {
        rtu::frame_gap(self.baud, self.parity != Parity::None, self.stop_bits)
    }

    /// The specification's silence between frames on this line.
    pub fn silence(&self) -> Duration {
        rtu::silence(self.baud, self.parity != Parity::None, self.stop_bits)
    }

    /// `/dev/ttyUSB0 19200 8E1`.
    pub fn describe(&self) -> String {
        let p = match self.parity {
            Parity::None => 'N',
            Parity::Even => 'E',
            Parity::Odd => 'O',
        };
        format!("{} {} 8{p}{}", self.device, self.baud, self.stop_bits)
    }

    /// Opens the port; reads wait at most `timeout` (then `TimedOut`).
    pub fn open(&self, timeout: Duration) -> Result<Box<dyn serialport::SerialPort>, String> {
        serialport::new(self.device.as_str(), self.baud)
            .data_bits(serialport::DataBits::Eight)
            .parity(match self.parity {
                Parity::None => serialport::Parity::None,
                Parity::Even => serialport::Parity::Even,
                Parity::Odd => serialport::Parity::Odd,
            })
            .stop_bits(if self.stop_bits == 2 {
                serialport::StopBits::Two
            } else {
                serialport::StopBits::One
            })
            .flow_control(serialport::FlowControl::None)
            .timeout(timeout)
            .open()
            .map_err(|e| format!("cannot open {}: {e}", self.describe()))
    }
}
