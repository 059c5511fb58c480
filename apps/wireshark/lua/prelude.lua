-- The prelude of the plugin: what the JAUS half (jaus.lua) and the Clearpath
-- half (clearpath.lua) share. The plugin is this file, then each half in a
-- block of its own after its generated tables (wireshark_plugin.cpp), so
-- these locals are seen by both and the halves' locals never meet.

-- Lua 5.2 (Wireshark 3.x/4.0) has bit32; later Lua has operators instead (kept in a string: 5.2 cannot parse them).
local bit32 = bit32 or load([[return {
  band = function(a, b) return a & b end, bxor = function(a, b) return a ~ b end,
  bnot = function(a) return ~a & 0xFFFFFFFF end, btest = function(a, b) return a & b ~= 0 end,
  lshift = function(a, n) return (a << n) & 0xFFFFFFFF end, rshift = function(a, n) return (a & 0xFFFFFFFF) >> n end,
  extract = function(a, f, w) return (a >> f) & ((1 << (w or 1)) - 1) end}]])()

-- A protocol's ProtoFields: field() makes one per abbreviation (once, however
-- often it is asked for) and lists it in fields, for proto.fields.
local function field_registry()
  local fields, field_of = {}, {}
  local function field(abbr, label, ftype, vs, base_, mask)
    local f = field_of[abbr]
    if f == nil then
      f = ProtoField.new(label, abbr, ftype, vs, base_, mask)
      field_of[abbr] = f
      fields[#fields + 1] = f
    end
    return f
  end
  return fields, field
end

-- The field type of an s-byte integer.
local function int_ftype(s, signed)
  if signed then return ({ftypes.INT8, ftypes.INT16, ftypes.INT24, ftypes.INT32, [8] = ftypes.INT64})[s] end
  return ({ftypes.UINT8, ftypes.UINT16, ftypes.UINT24, ftypes.UINT32, [8] = ftypes.UINT64})[s]
end

-- Code -> name of a generated message table, as a value string.
local function names_of(messages)
  local names = {}
  for code, m in pairs(messages) do names[code] = m.name end
  return names
end

-- The protocol on UDP: on the port of its preference "port" (0: none), again
-- whenever the preferences change, and on any port by its heuristic.
local function register_udp(proto, heuristic)
  local registered_port
  local function register_port()
    local udp = DissectorTable.get("udp.port")
    if registered_port and registered_port ~= 0 then udp:remove(registered_port, proto) end
    registered_port = proto.prefs.port
    if registered_port ~= 0 then udp:add(registered_port, proto) end
  end
  register_port()
  proto.prefs_changed = register_port
  proto:register_heuristic("udp", heuristic)
end
