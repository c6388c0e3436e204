# D3 example 3: an executive program, all of its list executed each scan.
-- P0.stl
SET   F0.0
RESET O1.0
LOAD  V50
TO    FW7
-- run
set 1: O1.0 = TRUE
expect 1: F0.0 = TRUE
expect 1: O1.0 = FALSE
expect 1: FW7 = 50
expect 1: F7.1 = TRUE
