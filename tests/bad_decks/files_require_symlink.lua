-- expect line 4: is a symbolic link out of its folder
-- A module in the deck's folder that is a symbolic link out of it (to /etc/passwd),
-- which Lua would parse and quote in its syntax error.
local secret = require("modules.passwd")
