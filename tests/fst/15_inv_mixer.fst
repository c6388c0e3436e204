# D3 example 15: the 16-station mixer. Every TP1 the stations that rested
# shake, where a container is present: LOAD OW1 INV AND IW1 TO OW1.
-- P0.stl
STEP 0
THEN  LOAD V2 TO TP1
STEP 10
IF    N T1
THEN  LOAD OW1
      INV
      AND IW1
      TO OW1
      SET T1
STEP 20
IF    N T1
THEN  JMP TO 10
-- run
set 1: IW1 = 5
expect 2: OW1 = 5
expect 2: P0.step = __FST_P0_STEPS#S20
expect 3: P0.step = __FST_P0_STEPS#S20
expect 4: P0.step = __FST_P0_STEPS#S10
expect 4: OW1 = 5
expect 5: OW1 = 0
expect 7: P0.step = __FST_P0_STEPS#S10
expect 8: OW1 = 5
