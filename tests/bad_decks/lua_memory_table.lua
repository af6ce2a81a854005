-- expect line 6: the deck used more than 64 MiB of Lua memory
-- args: --lua-memory 64
-- A table growing without end stops at the bound --lua-memory sets.
local rows = {}
for i = 1, 1e9 do
  rows[i] = { i, i }
end
