# D3 example 2: a parallel program P1 that runs once (ends with RESET P1).
-- P0.stl
STEP 0
THEN  SET P1
STEP 1
IF    F9.9
THEN  NOP
-- P1.stl
THEN  RESET F0.0
IF    N I1.0
THEN  SET O0.7
IF    I1.7
THEN  SET O1.7
OTHRW SET F0.0
      RESET O1.7
IF    F0.0
  AND I1.0
THEN  SET O1.0
      RESET P1
OTHRW RESET P1
-- run
# SET P1 in P0 starts P1, which runs in the same scan (number order), once.
set 1: I1.0 = TRUE
expect 1: P0.step = __FST_P0_STEPS#S1
expect 1: O0.7 = FALSE
expect 1: F0.0 = TRUE
expect 1: O1.0 = TRUE
expect 1: P1.run = FALSE
set 2: I1.0 = FALSE
expect 2: O0.7 = FALSE
expect 2: O1.0 = TRUE
