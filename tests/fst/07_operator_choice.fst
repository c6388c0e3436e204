# D3 example 7: STEP 40 jumps to 100, 150 or 200 when exactly one of
# I1.1, I1.2, I1.3 is on (conditions are evaluated left to right).
-- P0.stl
STEP 40
IF    I1.1 AND N I1.2 AND N I1.3
THEN  JMP TO 100
IF    N I1.1 AND I1.2 AND N I1.3
THEN  JMP TO 150
IF    N I1.1 AND N I1.2 AND I1.3
THEN  JMP TO 200
IF    NOP
THEN  JMP TO 40
STEP 100
THEN  SET O0.1
      JMP TO 40
STEP 150
THEN  SET O0.2
      JMP TO 40
STEP 200
THEN  SET O0.3
      JMP TO 40
-- run
set 1: I1.1 = TRUE
set 1: I1.2 = TRUE
expect 1: P0.step = __FST_P0_STEPS#S40
set 2: I1.2 = FALSE
expect 2: P0.step = __FST_P0_STEPS#S100
expect 3: O0.1 = TRUE
expect 3: P0.step = __FST_P0_STEPS#S40
set 4: I1.1 = FALSE
set 4: I1.3 = TRUE
expect 4: P0.step = __FST_P0_STEPS#S200
expect 5: O0.3 = TRUE
expect 5: O0.2 = FALSE
