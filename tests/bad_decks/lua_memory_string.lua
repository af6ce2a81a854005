-- expect line 3: the deck used more than 1024 MiB of Lua memory
-- One string of 1.5 GB is more than the default bound on the deck's Lua memory.
local s = string.rep("x", 1.5e9)
print(#s)
