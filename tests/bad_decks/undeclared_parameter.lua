-- expect line 0: command-line parameter 'speed' is not declared
-- args: speed=3
local model = tirefe.model{}
