# D3 example 11: STEP 60 IF I1.5 AND T7 AND N C2 THEN NOP advances when
# I1.5 is on, T7 is running and C2 has counted to CP2 (C2 back to 0).
-- P0.stl
STEP 59
THEN  LOAD V50 TO TP7
      LOAD V2 TO CP2
      SET T7
      SET C2
      SET P1
STEP 60
IF    I1.5 AND T7 AND N C2
THEN  NOP
STEP 61
THEN  SET O0.1
IF    F9.9
THEN  NOP
-- P1.stl
IF    I0.0
THEN  INC CW2
-- run
set 1: I1.5 = TRUE
expect 1: C2 = TRUE
expect 1: CW2 = 0
expect 1: T7 = TRUE
expect 2: P0.step = __FST_P0_STEPS#S60
set 3: I0.0 = TRUE
expect 3: CW2 = 1
expect 3: C2 = TRUE
expect 4: CW2 = 2
expect 4: C2 = FALSE
expect 4: P0.step = __FST_P0_STEPS#S60
expect 5: P0.step = __FST_P0_STEPS#S61
expect 5: O0.1 = FALSE
expect 6: O0.1 = TRUE
