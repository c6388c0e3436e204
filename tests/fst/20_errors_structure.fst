# Structure errors: a sentence that is not complete after the first, an
# unknown step, a missing module, bit and word mixed, CFM, a bad file name.
-- P0.stl
STEP 1
IF    I0.1
THEN  SET O0.1
THEN  SET O0.2
STEP 2
IF    IW0 AND I0.1
THEN  JMP TO 7
      CMP 5 WITH V1
      CFM 1
-- P99.stl
SET O0.1
-- errors
P0.stl:4: E186
P0.stl:6: E189
P0.stl:7: E186
P0.stl:8: E188
P0.stl:9: E188
P99.stl:1: E188
