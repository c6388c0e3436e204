# D3 example 16: SHIFT swaps a bit operand with the single-bit
# accumulator: on each press of I1.0, O1.1..O1.4 shift I1.1 in.
-- P0.stl
STEP 10
IF    I1.0
THEN  LOAD I1.1 TO F0.0
      SHIFT O1.1
      SHIFT O1.2
      SHIFT O1.3
      SHIFT O1.4
STEP 20
IF    N I1.0
THEN  NOP
-- run
set 1: I1.0 = TRUE
set 1: I1.1 = TRUE
expect 1: O1.1 = TRUE
expect 1: O1.2 = FALSE
expect 1: F0.0 = TRUE
set 2: I1.0 = FALSE
expect 2: P0.step = __FST_P0_STEPS#S10
set 3: I1.0 = TRUE
set 3: I1.1 = FALSE
expect 3: O1.1 = FALSE
expect 3: O1.2 = TRUE
set 4: I1.0 = FALSE
set 5: I1.0 = TRUE
set 5: I1.1 = TRUE
expect 5: O1.1 = TRUE
expect 5: O1.2 = FALSE
expect 5: O1.3 = TRUE
expect 5: O1.4 = FALSE
expect 5: SBA = FALSE
