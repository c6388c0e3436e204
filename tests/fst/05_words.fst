# D3 example 5: one LOAD to several destinations, masking, clearing words.
-- P0.stl
LOAD  V100 TO TP1 TO R10
LOAD  IW1 AND V$0F TO OW0
LOAD  V0 TO OW1 TO OW2 TO OW3
-- run
set 1: IW1 = 187
set 1: OW2 = 5
expect 1: TP1 = 100
expect 1: R10 = 100
expect 1: OW0 = 11
expect 1: O0.3 = TRUE
expect 1: O0.2 = FALSE
expect 1: OW2 = 0
expect 1: MBA = 0
