# D3 example 4: LOAD I1.0 TO O1.0 is IF I1.0 THEN SET O1.0 OTHRW RESET O1.0.
-- P0.stl
LOAD  I1.0 TO O1.0
LOAD  I1.0
AND   N I1.1
TO    O0.1
SET   P1
-- P1.stl
IF    I1.0
THEN  SET O2.0
OTHRW RESET O2.0
-- run
set 1: I1.0 = TRUE
expect 1: O1.0 = TRUE
expect 1: O0.1 = TRUE
expect 1: O2.0 = TRUE
expect 1: SBA = TRUE
set 2: I1.1 = TRUE
expect 2: O0.1 = FALSE
expect 2: O1.0 = TRUE
set 3: I1.0 = FALSE
expect 3: O1.0 = FALSE
expect 3: O2.0 = FALSE
