# D3 example 18, corrected: the program waits in step 1 with bec1 ON.
-- allocation.txt
I0.3 start
I0.4 stop
O0.2 bec1      lamp
-- P0.stl
STEP 0
IF    start THEN SET bec1
STEP 1
IF    stop THEN RESET bec1
-- run
set 1: start = TRUE
expect 1: bec1 = TRUE
expect 1: O0.2 = TRUE
expect 2: P0.step = __FST_P0_STEPS#S1
expect 2: bec1 = TRUE
