# D3 example 17 and the instruction table: SWAP, SHL, SHR, ROL, ROR, CPL,
# INV, BID, DEB on the multi-bit accumulator, arithmetic wrapping at 16
# bits, and the bare accumulator instructions.
-- P0.stl
LOAD  V$00FF SWAP TO R1
LOAD  V%0000000010000001 SHL TO R2
LOAD  V$8001 SHR TO R3
LOAD  V$8001 ROL TO R4
LOAD  V$8001 ROR TO R5
LOAD  V5 CPL TO R6
LOAD  V5 INV TO R7
LOAD  V1234 BID TO R8
LOAD  V$1234 DEB TO R9
LOAD  V65535 + V2 TO R10
LOAD  V3 - V5 TO R11
LOAD  V300 * V300 TO R12
LOAD  V7 / V2 TO R13
LOAD  V-1 TO R14
LOAD  V3 TO R15
SHL
INC
-- run
expect 1: R1 = 65280
expect 1: R2 = 258
expect 1: R3 = 16384
expect 1: R4 = 3
expect 1: R5 = 49152
expect 1: R6 = 65531
expect 1: R7 = 65530
expect 1: R8 = 4660
expect 1: R9 = 1234
expect 1: R10 = 1
expect 1: R11 = 65534
expect 1: R12 = 24464
expect 1: R13 = 3
expect 1: R14 = 65535
expect 1: R15 = 3
expect 1: MBA = 7
