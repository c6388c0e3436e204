# D3 example 8: priority wait loop. No input: JMP TO 60; I1.1 first (100),
# then I1.2 (150); only I1.3: NOP, the program falls through to STEP 70.
-- P0.stl
STEP 60
IF    N I1.1 AND N I1.2 AND N I1.3
THEN  JMP TO 60
IF    I1.1
THEN  JMP TO 100
IF    I1.2
THEN  JMP TO 150
IF    I1.3
THEN  NOP
STEP 70
THEN  SET O0.7
      JMP TO 60
STEP 100
THEN  SET O0.1
      JMP TO 60
STEP 150
THEN  SET O0.2
      JMP TO 60
-- run
expect 1: P0.step = __FST_P0_STEPS#S60
set 2: I1.2 = TRUE
set 2: I1.3 = TRUE
expect 2: P0.step = __FST_P0_STEPS#S150
expect 3: O0.2 = TRUE
expect 3: P0.step = __FST_P0_STEPS#S60
set 4: I1.2 = FALSE
expect 4: P0.step = __FST_P0_STEPS#S70
expect 5: O0.7 = TRUE
set 6: I1.1 = TRUE
set 6: I1.2 = TRUE
expect 6: P0.step = __FST_P0_STEPS#S100
