# D3 example 1: STEP init sets O0.1 and O0.2 when I0.1 AND N I0.2, then
# STEP 1's incomplete first sentence always runs before the next one.
-- P0.stl
STEP init
IF    I0.1
  AND N I0.2
THEN  SET O0.1
      SET O0.2
STEP 1
THEN  RESET O0.3
IF    I0.4
THEN  SET O0.3
-- run
set 1: I0.1 = TRUE
set 1: I0.2 = TRUE
set 1: O0.3 = TRUE
expect 1: O0.1 = FALSE
expect 1: P0.step = __FST_P0_STEPS#init
set 2: I0.2 = FALSE
expect 2: O0.1 = TRUE
expect 2: O0.2 = TRUE
expect 2: P0.step = __FST_P0_STEPS#S1
expect 3: O0.3 = FALSE
expect 3: P0.step = __FST_P0_STEPS#S1
set 4: I0.4 = TRUE
expect 4: O0.3 = TRUE
# after the last step the program starts again at its first step
expect 4: P0.step = __FST_P0_STEPS#init
set 5: I0.4 = FALSE
expect 5: P0.step = __FST_P0_STEPS#S1
expect 6: O0.3 = FALSE
