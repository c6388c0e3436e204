# The other diagnostics FST gives: an IF in an executive program, an
# unknown symbol, operands out of range, PSE, a bad allocation line.
-- allocation.txt
I0.1 Button
O0.1 TooLongName
-- P0.stl
SET   O0.1
IF    I0.1 THEN SET O0.2
-- P1.stl
IF    Foo
THEN  SET O0.1
IF    I0.1
THEN  SET O40.0
      SET T300
IF    I0.2
THEN  PSE
-- errors
P0.stl:2: E185
P1.stl:1: E182
P1.stl:4: E183
P1.stl:5: E183
P1.stl:7: E187
allocation.txt:2: E184
