# D3 example 9: IF NOP THEN SET T6 RESET F1.1. The timer counts TW6 down
# from TP6 in 0.01 s ticks of PLC time; T6 is 1 while it runs.
-- P0.stl
STEP 44
THEN  LOAD V3 TO TP6
      SET F1.1
STEP 45
IF    NOP
THEN  SET T6
      RESET F1.1
STEP 46
IF    N T6
THEN  SET O0.1
-- run
expect 1: F1.1 = TRUE
expect 1: TP6 = 3
expect 2: T6 = TRUE
expect 2: TW6 = 3
expect 2: F1.1 = FALSE
expect 3: TW6 = 2
expect 4: TW6 = 1
expect 4: O0.1 = FALSE
expect 5: T6 = FALSE
expect 5: TW6 = 0
expect 5: O0.1 = TRUE
expect 5: P0.step = __FST_P0_STEPS#S44
expect 5: TP6 = 3
