-- expect line 3: each 'step_windows' window is {from [s], to [s], dt [s]} with from < to and dt > 0
local body = { mass = 300 }
tirefe.vehicle{ body = body, corners = {}, duration = 1.0, dt = 1e-3, step_windows = { { 2.0, 1.5, 1e-4 } } }
