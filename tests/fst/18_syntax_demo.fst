# D3 example 18: the syntax-check demo's two errors.
-- allocation.txt
I0.3 start
I0.4 stop
O0.2 bec1      lamp
-- P0.stl
STEP 0
IF    start THEN SET I0.0
STEP 1
IF    stop THEN bec1
-- errors
P0.stl:2: E180
P0.stl:4: E181
