-- expect line 5: tread depth 2 mm is below the legal 1.6 mm plus margin
-- error() given a table with __tostring: its text is the message.
local failure = setmetatable({ depth = 2 },
  { __tostring = function(self) return "tread depth " .. self.depth .. " mm is below the legal 1.6 mm plus margin" end })
error(failure)
