-- expect line 10: this model was closed when Lua collected it
-- A finaliser stores a collected model in a global: the model is closed (its memory is
-- not freed under the deck), and a macro on it says so.
do
  local model = tirefe.model{ title = "kept by a finaliser" }
  setmetatable({}, { __gc = function() kept = model end })
end
collectgarbage()
collectgarbage()
kept:node{ x = 0, y = 0 }
