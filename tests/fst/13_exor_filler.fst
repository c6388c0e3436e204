# D3 example 13: the 8-bottle filler. The gate O1.0 closes and the dosers
# of bottles present but not full start (IW0 EXOR IW1); as the digest
# notes, OW0 is recomputed every pass while the gate is closed.
-- P0.stl
STEP 10
IF    N O1.0 AND I0.7
THEN  SET O1.0
      LOAD (IW0 EXOR IW1) TO OW0
STEP 20
IF    O1.0
THEN  LOAD IW0 EXOR IW1 TO OW0
IF    (OW0 = V0) AND O1.0
THEN  RESET O1.0
      JMP TO 10
-- run
set 1: IW0 = 255
expect 1: O1.0 = TRUE
expect 1: OW0 = 255
expect 1: P0.step = __FST_P0_STEPS#S20
expect 2: OW0 = 255
set 3: IW1 = 15
expect 3: OW0 = 240
expect 3: P0.step = __FST_P0_STEPS#S20
set 4: IW1 = 255
expect 4: OW0 = 0
expect 4: O1.0 = FALSE
expect 4: P0.step = __FST_P0_STEPS#S10
