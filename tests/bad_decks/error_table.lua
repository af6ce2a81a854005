-- expect line 4: error called with a table value instead of a message
-- error() given a table without __tostring: the message says so, at the deck line.
local checked = {}
error(checked)
