-- expect line 3: 'corners' lists at least one corner
local body = { mass = 300 }
tirefe.vehicle{ body = body, corners = {}, duration = 1.0, dt = 1e-3 }
