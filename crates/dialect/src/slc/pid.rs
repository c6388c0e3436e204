//! The PID instruction's run-time errors (SLC 5/03 and higher): the
//! sub-error code `__SLC_PID` (lib/slc.st) leaves in the high byte of
//! word 1 of the control block, each a major fault 0036h stopping the PLC.
//! The checks themselves are in `__SLC_PID`, in this order; the table
//! gives each code its fault message (docs/allen-bradley.md).

/// Sub-error code and what is wrong, by control-block word.
pub const ERRORS: [(u8, &str); 10] = [
    (0x11, "loop update time (word 13) outside 1 to 1024"),
    (0x12, "gain Kc (word 3) below 0"),
    (0x13, "reset Ti (word 4) below 0"),
    (0x14, "rate Td (word 5) below 0"),
    (0x23, "setpoint min (word 8) above setpoint max (word 7)"),
    (
        0x31,
        "setpoint (word 2) out of range at the first execution",
    ),
    (
        0x41,
        "dead band (word 9) below 0 or above the setpoint range",
    ),
    (0x51, "output max (word 11) outside 0 to 100 %"),
    (0x52, "output min (word 12) outside 0 to 100 %"),
    (0x53, "output min (word 12) above output max (word 11)"),
];
