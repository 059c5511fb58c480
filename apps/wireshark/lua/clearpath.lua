-- The fixed Lua of the Clearpath dissector: it reads CP_MESSAGES (type ->
-- name, kind and payload description) and CP_ACK, which the plugin defines
-- just before this file from the message descriptions
-- (apps/wireshark/clearpath_table.hpp), and uses the prelude's bit32,
-- field_registry, int_ftype, names_of and register_udp. It never names a
-- message or a field. Field abbreviations are clearpath.<message>.<field path>
-- (e.g. clearpath.set_velocity.translational); structural items end in .count
-- (list elements), .index (a record of a list) and .length (a text's length
-- byte). A command or request type is read as the host's message unless only
-- an ACK (2-byte result) explains it, as `jausctl clearpath decode` does, or as
-- an ACK when it comes from the platform port set in the preferences.
-- Malformed frames end in expert info, never in a Lua error.

local cp = Proto("clearpath", "Clearpath platform protocol")
cp.prefs.port = Pref.uint("UDP port", 0, "UDP port of a Clearpath platform (0: found by the frame's shape alone)")
cp.prefs.platform_port = Pref.uint("Platform UDP port", 0,
  "Frames from this UDP port come from the platform (command and request types are ACKs); 0: decide by the payload")

local fields, field = field_registry()

local TYPE_NAMES = names_of(CP_MESSAGES)
local ACK_BITS = {[0] = "bad checksum", "type not supported", "bad format", "out of range", "no bandwidth",
  "frequency too high", "too many message types"}

local hf = {
  length = field("clearpath.length", "Length", ftypes.UINT8),
  length_check = field("clearpath.length_check", "Length complement", ftypes.UINT8, nil, base.HEX),
  version = field("clearpath.version", "Version", ftypes.UINT8),
  timestamp = field("clearpath.timestamp", "Timestamp (ms)", ftypes.UINT32),
  flags = field("clearpath.flags", "Flags", ftypes.UINT8, nil, base.HEX),
  suppress_ack = field("clearpath.flags.suppress_ack", "Suppress ACK", ftypes.BOOLEAN, nil, 8, 0x01),
  type = field("clearpath.type", "Type", ftypes.UINT16, TYPE_NAMES, base.HEX),
  name = field("clearpath.name", "Message", ftypes.STRING),
  kind = field("clearpath.kind", "Kind", ftypes.STRING),
  acknowledges = field("clearpath.acknowledges", "Acknowledges", ftypes.STRING),
  result_text = field("clearpath.result_text", "Result", ftypes.STRING),
  payload = field("clearpath.payload", "Payload", ftypes.BYTES),
  crc = field("clearpath.crc", "CRC-16/CCITT-FALSE", ftypes.UINT16, nil, base.HEX),
  crc_expected = field("clearpath.crc.expected", "Expected CRC", ftypes.UINT16, nil, base.HEX),
}
local ef = {
  bad_crc = ProtoExpert.new("clearpath.bad_crc", "Bad CRC", expert.group.CHECKSUM, expert.severity.ERROR),
  malformed = ProtoExpert.new("clearpath.malformed", "Malformed Clearpath frame", expert.group.MALFORMED,
                              expert.severity.ERROR),
  unknown = ProtoExpert.new("clearpath.unknown_type", "Unknown type", expert.group.UNDECODED, expert.severity.WARN),
  nack = ProtoExpert.new("clearpath.ack_error", "ACK with an error", expert.group.RESPONSE_CODE, expert.severity.WARN),
}
cp.experts = {ef.bad_crc, ef.malformed, ef.unknown, ef.nack}

local prepare_body
local function prepare_field(d, a)
  d.a = a
  local label = d.n .. (d.unit and (" (" .. d.unit .. ")") or "")
  if d.k == "num" or d.k == "list" then
    d.f = field(a, label, d.scale and ftypes.DOUBLE or int_ftype(d.s, d.signed), d.vs, (not d.scale) and base.DEC or nil)
    if d.vs then d.fname = field(a .. ".name", d.n .. " (name)", ftypes.STRING) end
    if d.k == "list" then d.fcount = field(a .. ".count", d.n .. " count", ftypes.UINT8) end
  elseif d.k == "datetime" then
    d.f = field(a, label, ftypes.UINT32, nil, base.HEX)
    d.fname = field(a .. ".name", d.n .. " (date and time)", ftypes.STRING)
    d.parts = {}
    for _, p in ipairs({"year", "month", "day", "hour", "minute"}) do d.parts[p] = field(a .. "." .. p, p, ftypes.UINT16) end
  elseif d.k == "text" then
    d.f = field(a, label, ftypes.STRING)
    d.flength = field(a .. ".length", d.n .. " length", ftypes.UINT8)
    if d.nul then d.fnul = field(a .. "_nul_terminated", d.n .. " NUL terminated", ftypes.BOOLEAN) end
  elseif d.k == "flag" then
    d.f = field(a, label, ftypes.BOOLEAN)
  elseif d.k == "records" then
    if not d.implied then d.fcount = field(a .. ".count", d.n .. " count", ftypes.UINT8) end
    d.findex = field(a .. ".index", d.n .. " record", ftypes.UINT32)
    prepare_body(d.body, a)
  elseif d.k == "group" then
    d.f = field(a, label, ftypes.NONE)
    prepare_body(d.body, a)
  end
end
prepare_body = function(body, path)
  for _, d in ipairs(body) do prepare_field(d, path .. "." .. d.n) end
end
for t, m in pairs(CP_MESSAGES) do
  prepare_body(m.body, "clearpath." .. m.name)
  for _, b in pairs(m.by_size or {}) do prepare_body(b, "clearpath." .. m.name) end
end
prepare_body(CP_ACK, "clearpath.ack")
cp.fields = fields

-- ---- walking a payload (tree nil: a dry run that only checks the layout) ----

local function fail(c, text)
  c.failed = c.failed or text
  return false
end
local function need(c, n, d)
  if c.lim - c.off < n then return fail(c, string.format("%s: needs %d bytes, %d left", d.a, n, c.lim - c.off)) end
  return true
end
local function add(tree, ...)
  if tree then return tree:add(...) end
end

local walk_body
local K = {}

local function number(c, d, tree)
  local r = c.tvb(c.off, d.s)
  local raw = d.signed and r:le_int() or r:le_uint()
  c.off = c.off + d.s
  if d.scale then
    local item = add(tree, d.f, r, raw / d.scale)
    if item then item:append_text(string.format(" (raw %d)", raw)) end
  else
    local item = add(tree, d.f, r, raw)
    if item and d.vs and d.vs[raw] then item:add(d.fname, r, d.vs[raw]):set_generated() end
  end
end

K.num = function(c, d, tree)
  if not need(c, d.s, d) then return false end
  number(c, d, tree)
  return true
end

-- Minute bits 0-5, hour 6-10, day 11-16, month 17-20, year - 2000 21-27 (packed_date_time.hpp).
K.datetime = function(c, d, tree)
  if not need(c, d.s, d) then return false end
  local r = c.tvb(c.off, d.s)
  local raw = r:le_uint()
  c.off = c.off + d.s
  local item = add(tree, d.f, r)
  if item == nil then return true end
  local p = {year = 2000 + bit32.extract(raw, 21, 7), month = bit32.extract(raw, 17, 4), day = bit32.extract(raw, 11, 6),
             hour = bit32.extract(raw, 6, 5), minute = bit32.extract(raw, 0, 6)}
  for _, name in ipairs({"year", "month", "day", "hour", "minute"}) do item:add(d.parts[name], r, p[name]) end
  if bit32.rshift(raw, 28) == 0 and p.month >= 1 and p.month <= 12 and p.day >= 1 and p.day <= 31 and p.hour <= 23
      and p.minute <= 59 then
    local text = string.format("%04d-%02d-%02dT%02d:%02d", p.year, p.month, p.day, p.hour, p.minute)
    item:add(d.fname, r, text):set_generated()
    item:append_text(" (" .. text .. ")")
  end
  return true
end

K.text = function(c, d, tree)
  if not need(c, 1, d) then return false end
  local n = c.tvb(c.off, 1):uint()
  add(tree, d.flength, c.tvb(c.off, 1))
  c.off = c.off + 1
  if not need(c, n, d) then return false end
  local s = n > 0 and c.tvb(c.off, n):raw() or ""
  local nul = d.nul and s:sub(-1) == "\0"
  if nul then s = s:sub(1, -2) end
  if n > 0 then add(tree, d.f, c.tvb(c.off, n), s) else add(tree, d.f, s) end
  if d.nul then
    local item = add(tree, d.fnul, nul)
    if item then item:set_generated() end
  end
  c.off = c.off + n
  return true
end

K.flag = function(c, d, tree)
  local item = add(tree, d.f, d.v)
  if item then item:set_generated() end
  return true
end

K.list = function(c, d, tree)
  if not need(c, 1, d) then return false end
  local n = c.tvb(c.off, 1):uint()
  local item = add(tree, d.fcount, c.tvb(c.off, 1))
  c.off = c.off + 1
  if not need(c, n * d.s, d) then return false end
  for _ = 1, n do number(c, d, item) end
  return true
end

K.records = function(c, d, tree)
  local n, item
  if d.implied then
    item = tree
  else
    if not need(c, 1, d) then return false end
    n = c.tvb(c.off, 1):uint()
    item = add(tree, d.fcount, c.tvb(c.off, 1))
    c.off = c.off + 1
  end
  if d.implied then
    -- Records fill the rest of the payload; a partial last one is an error.
    local i = 0
    while c.off < c.lim do
      local rec = add(item, d.findex, i)
      if not walk_body(c, d.body, rec) then return false end
      i = i + 1
    end
    return true
  end
  local recs = {}
  for i = 1, n do recs[i] = add(item, d.findex, i - 1) or false end
  if d.columns then
    -- First field of every record, then the second field of every record, ...
    for _, f in ipairs(d.body) do
      for i = 1, n do
        if not K[f.k](c, f, recs[i] or nil) then return false end
      end
    end
  else
    for i = 1, n do
      if not walk_body(c, d.body, recs[i] or nil) then return false end
    end
  end
  return true
end

K.group = function(c, d, tree)
  local item = add(tree, d.f)
  return walk_body(c, d.body, item)
end

walk_body = function(c, body, tree)
  for _, d in ipairs(body) do
    if not K[d.k](c, d, tree) then return false end
  end
  return true
end

-- The whole payload walked, and nothing left over: the layout fits.
local function walk_payload(tvb, off, len, body, tree)
  local c = {tvb = tvb, off = off, lim = off + len}
  local ok, err = pcall(walk_body, c, body, tree)
  if not ok then return false, "dissector error: " .. tostring(err) end
  if c.failed then return false, c.failed end
  if c.off ~= c.lim then return false, string.format("%d bytes after the last field", c.lim - c.off) end
  return true
end

local function crc16(bytes)
  local crc = 0xFFFF
  for i = 1, #bytes do
    crc = bit32.bxor(crc, bit32.lshift(bytes:byte(i), 8))
    for _ = 1, 8 do
      if bit32.btest(crc, 0x8000) then
        crc = bit32.band(bit32.bxor(bit32.lshift(crc, 1), 0x1021), 0xFFFF)
      else
        crc = bit32.band(bit32.lshift(crc, 1), 0xFFFF)
      end
    end
  end
  return crc
end

local function kind_of(t)
  if t >= 0x0001 and t <= 0x3FFF then return "command" end
  if t >= 0x4000 and t <= 0x7FFF then return "request" end
  if t >= 0x8000 and t <= 0xBFFF then return "data" end
  return "unassigned"
end

local function ack_text(result)
  if result == 0 then return "ok" end
  local parts = {}
  for b = 0, 15 do
    if bit32.btest(result, 2 ^ b) then parts[#parts + 1] = ACK_BITS[b] or ("bit " .. b) end
  end
  return table.concat(parts, "|")
end

-- One frame at off (already checked: AA, LEN/~LEN, whole frame present).
local function dissect_frame(tvb, off, size, pinfo, tree)
  local root = tree:add(cp, tvb(off, size))
  local t = tvb(off + 9, 2):le_uint()
  root:add(hf.length, tvb(off + 1, 1))
  root:add(hf.length_check, tvb(off + 2, 1))
  root:add(hf.version, tvb(off + 3, 1))
  root:add_le(hf.timestamp, tvb(off + 4, 4))
  local fl = root:add(hf.flags, tvb(off + 8, 1))
  fl:add(hf.suppress_ack, tvb(off + 8, 1))
  root:add_le(hf.type, tvb(off + 9, 2))
  if tvb(off + 11, 1):uint() ~= 0x55 then
    root:add_proto_expert_info(ef.malformed, "no 0x55 (STX) where the header ends")
    return
  end
  local plen = size - 14
  local crc_item = root:add_le(hf.crc, tvb(off + size - 2, 2))
  local expected = crc16(tvb(off, size - 2):raw())
  if expected ~= tvb(off + size - 2, 2):le_uint() then
    crc_item:add(hf.crc_expected, tvb(off + size - 2, 2), expected):set_generated()
    crc_item:add_proto_expert_info(ef.bad_crc, string.format("CRC mismatch: expected 0x%04X", expected))
  end

  local m = CP_MESSAGES[t]
  local kind = kind_of(t)
  local body, name, is_ack = nil, nil, false
  if m then
    body = (m.by_size and m.by_size[plen]) or m.body
    name = m.name
  end
  local from_platform = cp.prefs.platform_port ~= 0 and pinfo.src_port == cp.prefs.platform_port
  if kind == "command" or kind == "request" then
    if from_platform or (plen == 2 and (body == nil or not walk_payload(tvb, off + 12, plen, body, nil))) then
      is_ack = true
    end
  end
  if is_ack then
    body, name = CP_ACK, "ack"
    root:add(hf.kind, "ack"):set_generated()
    root:add(hf.acknowledges, m and m.name or string.format("0x%04X", t)):set_generated()
  else
    root:add(hf.kind, kind):set_generated()
  end
  local shown = name or string.format("unknown (0x%04X)", t)
  root:add(hf.name, shown):set_generated()
  root:append_text(string.format(", %s (0x%04X)", shown, t))
  pinfo.cols.info:set(string.format("%s (0x%04X)%s", shown, t, is_ack and (" of " .. (m and m.name or "?")) or ""))

  if body == nil then
    local item = plen > 0 and root:add(hf.payload, tvb(off + 12, plen)) or root
    item:add_proto_expert_info(ef.unknown, string.format("type 0x%04X is not in the protocol document", t))
    return
  end
  local ok, why = walk_payload(tvb, off + 12, plen, body, root)
  if not ok then root:add_proto_expert_info(ef.malformed, why) end
  if is_ack and ok then
    local result = tvb(off + 12, 2):le_uint()
    local item = root:add(hf.result_text, ack_text(result))
    item:set_generated()
    if result ~= 0 then item:add_proto_expert_info(ef.nack, ack_text(result)) end
    pinfo.cols.info:append(": " .. ack_text(result))
  end
end

-- Frames from off on; false when the bytes do not start like a frame.
local function frame_size_at(tvb, off)
  local left = tvb:len() - off
  if left < 14 or tvb(off, 1):uint() ~= 0xAA then return nil end
  local len = tvb(off + 1, 1):uint()
  if len < 11 or bit32.bxor(len, 0xFF) ~= tvb(off + 2, 1):uint() then return nil end
  return len + 3
end

function cp.dissector(tvb, pinfo, tree)
  if frame_size_at(tvb, 0) == nil then return 0 end
  pinfo.cols.protocol:set("Clearpath")
  local off = 0
  while off < tvb:len() do
    local size = frame_size_at(tvb, off)
    if size == nil or size > tvb:len() - off then
      local item = tree:add(cp, tvb(off))
      item:add_proto_expert_info(ef.malformed, size and string.format("frame of %d bytes, %d left", size,
        tvb:len() - off) or "bytes that do not start a frame (AA, LEN, ~LEN)")
      break
    end
    local ok, err = pcall(dissect_frame, tvb, off, size, pinfo, tree)
    if not ok then tree:add(cp, tvb(off, size)):add_proto_expert_info(ef.malformed, "dissector error: " .. tostring(err)) end
    off = off + size
  end
  return tvb:len()
end

local function heuristic(tvb, pinfo, tree)
  local size = frame_size_at(tvb, 0)
  if size == nil or size > tvb:len() or tvb(11, 1):uint() ~= 0x55 then return false end
  cp.dissector(tvb, pinfo, tree)
  return true
end

register_udp(cp, heuristic)
