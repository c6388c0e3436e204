# D3 example 12: INC / DEC on a register, level-triggered (one count per
# scan while the input is on); words wrap at 16 bits.
-- P0.stl
IF    I1.3
THEN  INC R9
IF    I2.2 AND N I3.6
THEN  DEC R9
      SET O2.1
-- run
set 1: I1.3 = TRUE
expect 1: R9 = 1
set 2: I1.3 = FALSE
expect 2: R9 = 1
set 3: I1.3 = TRUE
expect 3: R9 = 2
set 4: I1.3 = FALSE
set 4: I2.2 = TRUE
expect 4: R9 = 1
expect 4: O2.1 = TRUE
expect 5: R9 = 0
expect 6: R9 = 65535
