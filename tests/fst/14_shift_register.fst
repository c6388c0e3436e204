# D3 example 14: the shift register. Once the operation timer T1 has
# finished, station bits whose quality sensor is off are cleared and the
# line indexes; while it moves, LOAD FW1 SHL + V1 TO FW1 shifts a new part
# in at station 1... (bit 0 here: F1.0).
-- P0.stl
STEP 20
THEN  LOAD V10 TO TP1
      SET T1
STEP 40
IF    N T1 AND N I2.1
THEN  RESET F1.1
IF    N T1 AND N I2.2
THEN  RESET F1.2
IF    N T1
THEN  SET O1.1
STEP 50
IF    N I2.0
THEN  LOAD FW1, SHL, + V1, TO FW1
STEP 60
IF    I2.0
THEN  RESET O1.1
      JMP TO 20
-- run
set 1: I2.0 = TRUE
set 1: I2.1 = TRUE
set 1: FW1 = 6
expect 1: T1 = TRUE
expect 10: T1 = TRUE
expect 10: TW1 = 1
expect 10: P0.step = __FST_P0_STEPS#S40
expect 11: T1 = FALSE
expect 11: FW1 = 2
expect 11: O1.1 = TRUE
expect 11: P0.step = __FST_P0_STEPS#S50
set 12: I2.0 = FALSE
expect 12: FW1 = 5
expect 12: F1.0 = TRUE
expect 12: F1.2 = TRUE
expect 12: P0.step = __FST_P0_STEPS#S60
set 13: I2.0 = TRUE
expect 13: O1.1 = FALSE
expect 13: P0.step = __FST_P0_STEPS#S20
