-- expect line 0: restart file '{here}/no_such.ckpt.h5' does not exist
-- args: --restart {here}/no_such.ckpt.h5
local model = tirefe.model{}
model:node{ x = 0, y = 0 }
