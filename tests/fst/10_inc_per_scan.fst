# D3 example 10: a continuously scanned step. T4 AND O1.6 counts CW3 once
# per scan; N I2.2 (E-stop, NC) jumps to 90, which waits for I2.2 AND I3.3.
-- P0.stl
STEP 10
THEN  LOAD V1000 TO TP4
STEP 11
IF    I1.4
THEN  SET T4
IF    I3.0
THEN  SET O1.6
OTHRW RESET O1.6
IF    T4 AND O1.6
THEN  INC CW3
IF    N I2.2
THEN  JMP TO 90
IF    NOP
THEN  JMP TO 11
STEP 90
IF    I2.2 AND I3.3
THEN  JMP TO 11
-- run
set 1: I2.2 = TRUE
set 1: I1.4 = TRUE
set 1: I3.0 = TRUE
expect 1: P0.step = __FST_P0_STEPS#S11
expect 2: CW3 = 1
expect 2: O1.6 = TRUE
set 3: I1.4 = FALSE
expect 3: CW3 = 2
expect 4: CW3 = 3
set 5: I2.2 = FALSE
expect 5: CW3 = 4
expect 5: P0.step = __FST_P0_STEPS#S90
expect 6: CW3 = 4
set 7: I2.2 = TRUE
set 7: I3.3 = TRUE
expect 7: P0.step = __FST_P0_STEPS#S11
expect 7: CW3 = 4
expect 8: CW3 = 5
expect 8: TW4 = 994
