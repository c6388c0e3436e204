# D3 example 6: emergency stop by JMP. STEP 20 jumps at once to 80 when
# the NC button I1.1 opens (the later sentences do not run); 80 waits for
# the release and the reset button I2.1.
-- P0.stl
STEP 20
IF    N I1.1
THEN  LOAD V0 TO OW0
      JMP TO 80
IF    I1.2
THEN  SET O0.1
IF    NOP
THEN  JMP TO 20
STEP 80
IF    I1.1
  AND I2.1
THEN  JMP TO 20
-- run
set 1: I1.1 = TRUE
set 1: I1.2 = TRUE
set 1: O0.5 = TRUE
expect 1: O0.1 = TRUE
expect 1: P0.step = __FST_P0_STEPS#S20
set 2: I1.1 = FALSE
expect 2: OW0 = 0
expect 2: P0.step = __FST_P0_STEPS#S80
set 3: I1.1 = TRUE
expect 3: P0.step = __FST_P0_STEPS#S80
expect 3: O0.1 = FALSE
set 4: I2.1 = TRUE
expect 4: P0.step = __FST_P0_STEPS#S20
expect 4: O0.1 = FALSE
expect 5: O0.1 = TRUE
