-- The fixed Lua of the JAUS dissector: it reads MESSAGES (code -> name and
-- body description), which the plugin defines just before this file from the
-- message descriptions (apps/wireshark/jaus_table.hpp), and uses the
-- prelude's bit32, field_registry, int_ftype, names_of and register_udp.
-- AS5669A datagrams (SAE JAUS, version byte 0x02) on the same port are
-- jss.lua's, which follows this file in the same block and uses its walkers;
-- register.lua then registers the protocol's fields and the port.
-- It never names a message or a field. Field abbreviations are
-- jaus.<message>.<field path> (e.g. jaus.report_global_pose.latitude_deg);
-- the structural items of a body end in .pv (presence vector, with one bit
-- per optional field), .count (elements of a list), .index (a record of a
-- list) and .length (a size prefix); enumerated values get a generated .name
-- beside their number. Malformed input ends in expert info, never in a Lua
-- error (the body walk runs under pcall).

local jaus = Proto("jaus", "JAUS RA 3.x")
local OPENJAUS = 1
jaus.prefs.dialect = Pref.enum("Dialect", 0,
  "ra: Part 3 as written; openjaus: the quirks of the common open RA 3.3 implementation (docs/messages.md)",
  {{1, "ra", 0}, {2, "openjaus", OPENJAUS}}, false)
jaus.prefs.port = Pref.uint("UDP port", 3794, "UDP port of JAUS (OPC and JUDP framings; any port is also found by its framing)")
jaus.prefs.reassemble = Pref.bool("Reassemble large data sets", true,
  "Show the whole message of a large data set on its last packet (reassembled in capture order)")

local fields, field = field_registry()

local ACK_NAK = {[0] = "none", [1] = "ack_requested", [2] = "nak", [3] = "ack"}
local DATA_FLAGS = {[0] = "single", [1] = "first", [2] = "middle", [4] = "retransmitted", [8] = "last"}
local LIMIT_TYPES = {[0] = "byte", [1] = "short_integer", [2] = "integer", [3] = "long_integer",
  [4] = "unsigned_short", [5] = "unsigned_integer", [6] = "unsigned_long", [7] = "float32", [8] = "float64", [9] = "rgb"}
local LIMIT_SIZES = {[0] = 1, [1] = 2, [2] = 4, [3] = 8, [4] = 2, [5] = 4, [6] = 8, [7] = 4, [8] = 8, [9] = 3}

local CODE_NAMES = names_of(MESSAGES)

local hf = {
  framing = field("jaus.framing", "Framing", ftypes.STRING),
  judp_version = field("jaus.judp.version", "JUDP transport version", ftypes.UINT8),
  judp_compression = field("jaus.judp.header_compression", "JUDP header compression", ftypes.UINT8),
  judp_flags = field("jaus.judp.compression_flags", "JUDP compression flags", ftypes.UINT8),
  judp_length = field("jaus.judp.length", "JUDP message length", ftypes.UINT16),
  header = field("jaus.header", "Header", ftypes.NONE),
  priority = field("jaus.priority", "Priority", ftypes.UINT16, nil, base.DEC, 0x000F),
  ack_nak = field("jaus.ack_nak", "ACK/NAK", ftypes.UINT16, ACK_NAK, base.DEC, 0x0030),
  service_connection = field("jaus.service_connection", "Service connection", ftypes.BOOLEAN, nil, 16, 0x0040),
  experimental = field("jaus.experimental", "Experimental", ftypes.BOOLEAN, nil, 16, 0x0080),
  version = field("jaus.version", "Version", ftypes.UINT16, {[1] = "RA 3.0/3.1", [2] = "RA 3.2/3.3"}, base.DEC, 0x3F00),
  code = field("jaus.code", "Command code", ftypes.UINT16, CODE_NAMES, base.HEX),
  name = field("jaus.name", "Message", ftypes.STRING),
  destination = field("jaus.destination", "Destination", ftypes.STRING),
  source = field("jaus.source", "Source", ftypes.STRING),
  data_size = field("jaus.data_size", "Data size", ftypes.UINT16, nil, base.DEC, 0x0FFF),
  data_flag = field("jaus.data_flag", "Data flag", ftypes.UINT16, DATA_FLAGS, base.DEC, 0xF000),
  sequence = field("jaus.sequence", "Sequence number", ftypes.UINT16),
  body = field("jaus.body", "Body", ftypes.NONE),
  inner = field("jaus.inside", "Message inside", ftypes.NONE),
  payload = field("jaus.payload", "Payload", ftypes.BYTES),
  lds_packets = field("jaus.large_data_set.packets", "Large data set packets", ftypes.UINT32),
  lds_length = field("jaus.large_data_set.length", "Large data set length", ftypes.UINT32),
  lds_first_frame = field("jaus.large_data_set.first_frame", "Large data set first packet", ftypes.FRAMENUM),
}

local ef = {
  malformed = ProtoExpert.new("jaus.malformed", "Malformed JAUS message", expert.group.MALFORMED, expert.severity.ERROR),
  unknown = ProtoExpert.new("jaus.unknown_code", "Unknown command code", expert.group.UNDECODED, expert.severity.WARN),
  trailing = ProtoExpert.new("jaus.trailing", "Trailing bytes", expert.group.MALFORMED, expert.severity.WARN),
  header = ProtoExpert.new("jaus.bad_header", "Bad JAUS header", expert.group.MALFORMED, expert.severity.ERROR),
  lds = ProtoExpert.new("jaus.large_data_set", "Packet of a large data set", expert.group.REASSEMBLE, expert.severity.NOTE),
}

-- ---- ProtoFields of the generated descriptions -----------------------------

local prepare_body
local function prepare_field(d, a, label)
  d.a = a
  local k = d.k
  if k == "int" or k == "dim" then
    d.f = field(a, label, int_ftype(d.s, d.signed), d.vs, base.DEC)
    if d.vs then d.fname = field(a .. ".name", label .. " (name)", ftypes.STRING) end
  elseif k == "flags" then
    d.f = field(a, label, int_ftype(d.s, false), nil, base.HEX)
    for _, b in ipairs(d.bits) do
      local mask = (2 ^ b.width - 1) * 2 ^ b.first
      if b.width == 1 then
        b.f = field(a .. "." .. b.n, b.n, ftypes.BOOLEAN, nil, 8 * d.s, mask)
      else
        b.f = field(a .. "." .. b.n, b.n, int_ftype(d.s, false), b.vs, base.DEC, mask)
        if b.vs then b.fname = field(a .. "." .. b.n .. ".name", b.n .. " (name)", ftypes.STRING) end
      end
    end
    d.fother = field(a .. ".other_bits", "other bits", int_ftype(d.s, false), nil, base.HEX)
  elseif k == "real" then
    d.f = field(a, label, d.s == 4 and ftypes.FLOAT or ftypes.DOUBLE)
  elseif k == "scaled" or k == "linear" then
    d.f = field(a, label, ftypes.DOUBLE)
  elseif k == "text" or k == "address" then
    d.f = field(a, label, ftypes.STRING)
  elseif k == "time" then
    d.f = field(a, label, ftypes.UINT32, nil, base.HEX)
    d.parts = {}
    for _, p in ipairs({"day", "hour", "minute", "second", "millisecond"}) do
      d.parts[p] = field(a .. "." .. p, p, ftypes.UINT16)
    end
  elseif k == "date" then
    d.f = field(a, label, ftypes.UINT16, nil, base.HEX)
    d.parts = {}
    for _, p in ipairs({"year", "month", "day"}) do d.parts[p] = field(a .. "." .. p, p, ftypes.UINT16) end
  elseif k == "bytes" then
    d.f = field(a, label, ftypes.BYTES)
    if d.size > 0 then d.flength = field(a .. ".length", label .. " length", int_ftype(d.size, false)) end
  elseif k == "limit" then
    d.f = field(a, label, ftypes.NONE)
    d.ftype = field(a .. ".type", "type", ftypes.UINT8, LIMIT_TYPES, base.DEC)
    d.fbits = field(a .. ".bits", "bits", ftypes.UINT64, nil, base.HEX)
  elseif k == "array" then
    d.fcount = field(a .. ".count", label .. " count", ftypes.UINT32)
    prepare_field(d.elem, a, label)
  elseif k == "records" then
    d.fcount = field(a .. ".count", label .. " count", ftypes.UINT32)
    d.findex = field(a .. ".index", label .. " record", ftypes.UINT32)
    prepare_body(d.body, a)
  end
end

prepare_body = function(body, path)
  local mask = 0
  for _, d in ipairs(body) do
    if d.bit then mask = mask + 2 ^ d.bit end
  end
  for _, d in ipairs(body) do
    if d.k == "pv" then
      d.a = path .. ".pv"
      d.mask = mask
      d.f = field(d.a, "Presence vector", int_ftype(d.s, false), nil, base.HEX)
      d.bitf = {}
      for _, o in ipairs(body) do
        if o.bit then
          d.bitf[#d.bitf + 1] = field(d.a .. "." .. o.n, o.n, ftypes.BOOLEAN, {"present", "absent"}, 8 * d.s, 2 ^ o.bit)
        end
      end
    else
      prepare_field(d, path .. "." .. d.n, d.n)
    end
  end
end

for code, m in pairs(MESSAGES) do
  m.slug = m.name:lower():gsub("[^%w]+", "_")
  m.code = code
  prepare_body(m.body, "jaus." .. m.slug)
end

-- ---- walking a body ---------------------------------------------------------

local function fail(c, item, text)
  if not c.failed then
    c.failed = text
    item:add_proto_expert_info(ef.malformed, text)
  end
  return false
end

local function need(c, n, d, item)
  if c.lim - c.off < n then
    return fail(c, item, string.format("%s: needs %d bytes, %d left", d.a, n, c.lim - c.off))
  end
  return true
end

local function uint_at(c, s)
  if s == 8 then return c.tvb(c.off, 8):le_uint64() end
  return c.tvb(c.off, s):le_uint()
end
local function int_at(c, s)
  if s == 8 then return c.tvb(c.off, 8):le_int64() end
  return c.tvb(c.off, s):le_int()
end

-- Bytes a list element takes at least (to refuse counts that cannot fit).
local function min_size(d)
  if d.s then return d.s end
  return 1
end

local walk_body
local K = {}

K.int = function(c, d, tree)
  if not need(c, d.s, d, tree) then return false end
  local r = c.tvb(c.off, d.s)
  local v = d.signed and int_at(c, d.s) or uint_at(c, d.s)
  local item = tree:add_le(d.f, r)
  -- The name, or the number when the value has none (as the codec's JSON shows it).
  if d.vs then item:add(d.fname, r, d.vs[v] or tostring(v)):set_generated() end
  c.values[d.n or d.a] = v
  c.off = c.off + d.s
  return true
end

K.dim = function(c, d, tree)
  local start = c.off
  if not K.int(c, d, tree) then return false end
  local v = c.tvb(start, d.s):le_uint()
  c.dims[d.dim] = v
  if v < d.min then return fail(c, tree, string.format("%s: %d < %d", d.a, v, d.min)) end
  return true
end

K.flags = function(c, d, tree)
  if not need(c, d.s, d, tree) then return false end
  local r = c.tvb(c.off, d.s)
  local v = uint_at(c, d.s)
  local item = tree:add_le(d.f, r)
  local covered = 0
  for _, b in ipairs(d.bits) do
    local sub = item:add_le(b.f, r)
    covered = covered + (2 ^ b.width - 1) * 2 ^ b.first
    if b.vs then
      local part = bit32.extract(v, b.first, b.width)
      if b.vs[part] then sub:add(b.fname, r, b.vs[part]):set_generated() end
    end
  end
  local other = bit32.band(v, bit32.bnot(covered))
  if other ~= 0 then item:add(d.fother, r, other):set_generated() end
  c.off = c.off + d.s
  return true
end

K.real = function(c, d, tree)
  if not need(c, d.s, d, tree) then return false end
  tree:add_le(d.f, c.tvb(c.off, d.s))
  c.off = c.off + d.s
  return true
end

-- The scaled-integer rule (docs/wire-format.md, "Scaled integers"), as the codec computes it (core/scaled_integer.hpp).
K.scaled = function(c, d, tree)
  if not need(c, d.s, d, tree) then return false end
  local peer = c.dialect == OPENJAUS
  local signed = d.signed and not (d.quirk and peer)
  local raw = signed and int_at(c, d.s) or uint_at(c, d.s)
  local full = 2 ^ (8 * d.s) - 1
  local steps = (signed or (peer and d.s == 4)) and full - 1 or full
  local scale = (d.hi - d.lo) / steps
  local bias = signed and (d.hi + d.lo) / 2 or d.lo
  local v
  if signed and raw == -2 ^ (8 * d.s - 1) then v = d.lo else v = raw * scale + bias end
  local item = tree:add(d.f, c.tvb(c.off, d.s), v)
  item:append_text(string.format(" (raw %d)", raw))
  c.off = c.off + d.s
  return true
end

K.linear = function(c, d, tree)
  if not need(c, d.s, d, tree) then return false end
  local raw = d.signed and int_at(c, d.s) or uint_at(c, d.s)
  local item = tree:add(d.f, c.tvb(c.off, d.s), raw * d.factor)
  item:append_text(string.format(" (raw %d)", raw))
  c.off = c.off + d.s
  return true
end

K.text = function(c, d, tree)
  local n = d.len
  if d.shorter then n = math.min(n, c.lim - c.off) end
  if not need(c, n, d, tree) then return false end
  if n == 0 then
    tree:add(d.f, "")
    return true
  end
  local r = c.tvb(c.off, n)
  local s = r:raw()
  local nul = s:find("\0", 1, true)
  if nul then s = s:sub(1, nul - 1) end
  tree:add(d.f, r, s)
  c.off = c.off + n
  return true
end

K.time = function(c, d, tree)
  if not need(c, 4, d, tree) then return false end
  local r = c.tvb(c.off, 4)
  local raw = r:le_uint()
  local p = {day = bit32.extract(raw, 27, 5), hour = bit32.extract(raw, 22, 5), minute = bit32.extract(raw, 16, 6),
             second = bit32.extract(raw, 10, 6), millisecond = bit32.extract(raw, 0, 10)}
  local item = tree:add_le(d.f, r)
  item:append_text(string.format(" (day %d, %02d:%02d:%02d.%03d)", p.day, p.hour, p.minute, p.second, p.millisecond))
  for _, name in ipairs({"day", "hour", "minute", "second", "millisecond"}) do item:add(d.parts[name], r, p[name]) end
  c.off = c.off + 4
  return true
end

K.date = function(c, d, tree)
  if not need(c, 2, d, tree) then return false end
  local r = c.tvb(c.off, 2)
  local raw = r:le_uint()
  local p = {day = bit32.extract(raw, 0, 5), month = bit32.extract(raw, 5, 4), year = 2000 + bit32.extract(raw, 9, 7)}
  if c.dialect == OPENJAUS then
    -- It sends a 0-based month and the calendar year's low 7 bits (core/wire/codecs.hpp, Date).
    p.month = p.month + 1
    p.year = 2000 + ((((p.year - 2000) % 128) + 128 - 80) % 128)
  end
  local item = tree:add_le(d.f, r)
  item:append_text(string.format(" (%04d-%02d-%02d)", p.year, p.month, p.day))
  for _, name in ipairs({"year", "month", "day"}) do item:add(d.parts[name], r, p[name]) end
  c.off = c.off + 2
  return true
end

K.bytes = function(c, d, tree)
  local n = c.lim - c.off
  if d.size > 0 then
    if not need(c, d.size, d, tree) then return false end
    n = c.tvb(c.off, d.size):le_uint()
    tree:add_le(d.flength, c.tvb(c.off, d.size))
    c.off = c.off + d.size
    if n > c.lim - c.off then
      return fail(c, tree, string.format("%s: size %d but %d bytes left", d.a, n, c.lim - c.off))
    end
  end
  if n == 0 then
    tree:add(d.f, "")  -- an empty FT_BYTES value without a range is given as a string
    return true
  end
  local r = c.tvb(c.off, n)
  tree:add(d.f, r)
  c.ranges[d.n] = r
  c.off = c.off + n
  return true
end

K.address = function(c, d, tree)
  if not need(c, 4, d, tree) then return false end
  local r = c.tvb(c.off, 4)
  local s = string.format("%d.%d.%d.%d", r(0, 1):uint(), r(1, 1):uint(), r(2, 1):uint(), r(3, 1):uint())
  tree:add(d.f, r, s)
  c.off = c.off + 4
  return true
end

K.limit = function(c, d, tree)
  if not need(c, 1, d, tree) then return false end
  local t = c.tvb(c.off, 1):uint()
  local size = LIMIT_SIZES[t]
  if size == nil then return fail(c, tree, string.format("%s: event limit type %d", d.a, t)) end
  if not need(c, 1 + size, d, tree) then return false end
  local item = tree:add(d.f, c.tvb(c.off, 1 + size))
  item:add(d.ftype, c.tvb(c.off, 1))
  local r = c.tvb(c.off + 1, size)
  local bits = size == 8 and r:le_uint64() or UInt64(r:le_uint())
  item:add(d.fbits, r, bits)
  local shown
  if t == 7 then shown = r:le_float() elseif t == 8 then shown = r:le_double()
  elseif t == 0 or t == 4 or t == 5 or t == 6 or t == 9 then shown = tostring(bits)
  else shown = tostring(size == 8 and r:le_int64() or r:le_int()) end
  item:append_text(string.format(": %s %s", LIMIT_TYPES[t], tostring(shown)))
  c.off = c.off + 1 + size
  return true
end

-- A list's element count: from its prefix, or from a count sent earlier (Dimension).
local function read_count(c, d, tree)
  local cnt = d.count
  if cnt.s then
    if not need(c, cnt.s, d, tree) then return nil end
    local r = c.tvb(c.off, cnt.s)
    local n = r:le_uint()
    local item = tree:add(d.fcount, r, n)
    c.off = c.off + cnt.s
    if n < cnt.min or n > cnt.max then
      fail(c, item, string.format("%s: count %d, allowed %d-%d", d.a, n, cnt.min, cnt.max))
      return nil
    end
    return n, item
  end
  local n = math.max((c.dims[cnt.dim] or 0) - cnt.less, 0)
  local item = tree:add(d.fcount, n)
  item:set_generated()
  return n, item
end

K.array = function(c, d, tree)
  local n, item = read_count(c, d, tree)
  if n == nil then return false end
  if n > (c.lim - c.off) / min_size(d.elem) then
    return fail(c, item, string.format("%s: %d elements cannot fit in %d bytes", d.a, n, c.lim - c.off))
  end
  local kind = K[d.elem.k]
  for _ = 1, n do
    if not kind(c, d.elem, item) then return false end
  end
  return true
end

K.records = function(c, d, tree)
  local n, item = read_count(c, d, tree)
  if n == nil then return false end
  if n > c.lim - c.off then
    return fail(c, item, string.format("%s: %d records cannot fit in %d bytes", d.a, n, c.lim - c.off))
  end
  for i = 1, n do
    local start = c.off
    local rec = item:add(d.findex, c.tvb(c.off, math.min(1, c.lim - c.off)), i - 1)
    if not walk_body(c, d.body, rec) then return false end
    rec:set_len(c.off - start)
  end
  return true
end

walk_body = function(c, body, tree)
  local pv = 0
  for _, d in ipairs(body) do
    if d.k == "pv" then
      if not need(c, d.s, d, tree) then return false end
      local r = c.tvb(c.off, d.s)
      pv = r:le_uint()
      local item = tree:add_le(d.f, r)
      for _, b in ipairs(d.bitf) do item:add_le(b, r) end
      c.off = c.off + d.s
      local reserved = bit32.band(pv, bit32.bnot(d.mask))
      if reserved ~= 0 then
        -- The layout after an unknown bit cannot be known (as the codec says: reserved_presence_bits).
        return fail(c, item, string.format("%s: reserved presence bits 0x%X (defined 0x%X)", d.a, reserved, d.mask))
      end
    else
      local present = true
      if d.only then
        present = (d.only == "openjaus") == (c.dialect == OPENJAUS)
      elseif d.bit then
        present = bit32.extract(pv, d.bit) == 1
      end
      if present and not K[d.k](c, d, tree) then return false end
    end
  end
  return true
end

-- ---- a message ---------------------------------------------------------------

local dissect_body

-- Event (0x41F1) carries a report's payload, Create/Update Event a query's.
local function dissect_inside(c, code, pinfo, tree)
  local r, inner
  if code == 0x41F1 then
    r, inner = c.ranges.report_message, c.values.report_code
  elseif code == 0x01F0 or code == 0x01F1 then
    r, inner = c.ranges.query_message, c.values.report_code and c.values.report_code - 0x2000
  end
  if r == nil or inner == nil then return end
  local m = MESSAGES[inner]
  local item = tree:add(hf.inner, r)
  item:set_text(string.format("Message inside: %s (0x%04X)", m and m.name or "unknown", inner))
  dissect_body(r:tvb(), 0, r:len(), inner, pinfo, item)
end

dissect_body = function(tvb, off, len, code, pinfo, tree)
  local m = MESSAGES[code]
  if m == nil then
    local item = len > 0 and tree:add(hf.payload, tvb(off, len)) or tree
    item:add_proto_expert_info(ef.unknown, string.format("Unknown command code 0x%04X: payload not dissected", code))
    return
  end
  local item = len > 0 and tree:add(hf.body, tvb(off, len)) or tree:add(hf.body)
  item:set_text(string.format("%s (0x%04X)", m.name, code))
  local c = {tvb = tvb, off = off, lim = off + len, dialect = jaus.prefs.dialect, dims = {}, values = {}, ranges = {}}
  local ok, err = pcall(walk_body, c, m.body, item)
  if not ok then
    item:add_proto_expert_info(ef.malformed, "dissector error: " .. tostring(err))
    return
  end
  if c.failed then return end
  if c.off < c.lim then
    item:add_proto_expert_info(ef.trailing, string.format("%d bytes after the last field", c.lim - c.off))
  end
  dissect_inside(c, code, pinfo, item)
end

-- Large messages of both dialects (RA's large data sets, JSS's large
-- messages): packets by key in capture order, collected on the first pass.
-- The first packet starts one, each next sequence number adds to it, the
-- last completes it, kept under `done_key`; a retransmission of the packet
-- just received adds nothing; anything else drops what was collected.
local pending, reassembled = {}, {}

local function collect_packet(key, done_key, flags, tvb, off, size, flag, seq, pinfo)
  if pinfo.visited then return end
  local p = pending[key]
  if flag == flags.first then
    pending[key] = {next = (seq + 1) % 65536, data = tvb(off, size):bytes(), packets = 1, first = pinfo.number}
  elseif p and seq == p.next then
    p.data:append(tvb(off, size):bytes())
    p.next = (seq + 1) % 65536
    p.packets = p.packets + 1
    if flag == flags.last then
      reassembled[done_key] = p
      pending[key] = nil
    end
  elseif p and flag == flags.retransmitted and seq == (p.next + 65535) % 65536 then
    -- A retransmission of the packet just received: nothing new.
  else
    pending[key] = nil
  end
end

-- The whole message of which this is the last packet (when reassembly is
-- on), its packet count, length and first frame shown under `tree`; else nil.
local function reassembled_tvb(done_key, tree, label)
  local whole = reassembled[done_key]
  if not (whole and jaus.prefs.reassemble) then return nil end
  local rtvb = whole.data:tvb(label)
  tree:add(hf.lds_packets, whole.packets):set_generated()
  tree:add(hf.lds_length, whole.data:len()):set_generated()
  tree:add(hf.lds_first_frame, whole.first):set_generated()
  return rtvb
end

-- RA: by (source, destination, code); data flags 1 first, 2 middle, 4 retransmitted, 8 last.
local RA_LDS_FLAGS = {first = 1, last = 8, retransmitted = 4}

local function large_data_set(tvb, off, size, code, flag, seq, src, dst, pinfo, tree)
  collect_packet(src .. ">" .. dst .. ":" .. code, pinfo.number, RA_LDS_FLAGS, tvb, off, size, flag, seq, pinfo)
  tree:add_proto_expert_info(ef.lds, string.format("Large data set packet (%s, sequence %d)", DATA_FLAGS[flag] or flag, seq))
  local rtvb = reassembled_tvb(pinfo.number, tree, "Reassembled large data set")
  if rtvb then
    dissect_body(rtvb, 0, rtvb:len(), code, pinfo, tree)
    return true
  end
  if size > 0 then tree:add(hf.payload, tvb(off, size)) end
  return false
end

local function address_at(tvb, off)
  return string.format("%d.%d.%d.%d", tvb(off + 3, 1):uint(), tvb(off + 2, 1):uint(), tvb(off + 1, 1):uint(),
                       tvb(off, 1):uint())
end

local function dissect_message(tvb, off, pinfo, tree, root)
  local avail = tvb:len() - off
  if avail < 16 then
    root:add_proto_expert_info(ef.header, string.format("%d bytes: shorter than a JAUS header (16)", avail))
    return
  end
  local props = tvb(off, 2):le_uint()
  local code = tvb(off + 2, 2):le_uint()
  local dst, src = address_at(tvb, off + 4), address_at(tvb, off + 8)
  local control = tvb(off + 12, 2):le_uint()
  local size, flag = bit32.band(control, 0x0FFF), bit32.rshift(control, 12)
  local seq = tvb(off + 14, 2):le_uint()
  local m = MESSAGES[code]
  local name = m and m.name or string.format("Unknown (0x%04X)", code)
  root:append_text(string.format(", %s, %s -> %s", name, src, dst))
  pinfo.cols.info:set(string.format("%s (0x%04X) %s -> %s", name, code, src, dst))
  if flag ~= 0 then pinfo.cols.info:append(string.format(" [%s, seq %d]", DATA_FLAGS[flag] or flag, seq)) end

  local h = root:add(hf.header, tvb(off, 16))
  h:add_le(hf.priority, tvb(off, 2))
  h:add_le(hf.ack_nak, tvb(off, 2))
  h:add_le(hf.service_connection, tvb(off, 2))
  h:add_le(hf.experimental, tvb(off, 2))
  local vitem = h:add_le(hf.version, tvb(off, 2))
  h:add_le(hf.code, tvb(off + 2, 2))
  h:add(hf.name, tvb(off + 2, 2), name):set_generated()
  h:add(hf.destination, tvb(off + 4, 4), dst)
  h:add(hf.source, tvb(off + 8, 4), src)
  local sitem = h:add_le(hf.data_size, tvb(off + 12, 2))
  local fitem = h:add_le(hf.data_flag, tvb(off + 12, 2))
  h:add_le(hf.sequence, tvb(off + 14, 2))

  local version = bit32.extract(props, 8, 6)
  if version ~= 1 and version ~= 2 then
    vitem:add_proto_expert_info(ef.header, string.format("version %d (1 or 2 expected)", version))
  end
  if DATA_FLAGS[flag] == nil then
    fitem:add_proto_expert_info(ef.header, string.format("unknown data flag %d", flag))
    return
  end
  if size > 4080 then sitem:add_proto_expert_info(ef.header, string.format("data size %d > 4080", size)) end
  if size ~= avail - 16 then
    sitem:add_proto_expert_info(ef.header, string.format("data size %d but %d bytes follow the header", size, avail - 16))
    if size > avail - 16 then return end
  end
  if flag ~= 0 then
    large_data_set(tvb, off + 16, size, code, flag, seq, src, dst, pinfo, root)
    return
  end
  dissect_body(tvb, off + 16, size, code, pinfo, root)
end

local OPC = "JAUS01.0"
local AS5669A = 2

-- The framing by its prefix (a short message after it is reported, not skipped).
local function framing_of(tvb)
  if tvb:len() >= 8 and tvb(0, 8):string() == OPC then return "OPC" end
  if tvb:len() >= 5 and tvb(0, 1):uint() == 1 and tvb(1, 2):uint() == 0 then return "JUDP" end
  if tvb:len() >= 1 and tvb(0, 1):uint() == AS5669A then return "AS5669A" end
  return nil
end

-- AS5669A datagrams: jss.lua.
local dissect_as5669a

function jaus.dissector(tvb, pinfo, tree)
  local framing = framing_of(tvb)
  if framing == nil then return 0 end
  local root = tree:add(jaus, tvb())
  if framing == "AS5669A" then
    pinfo.cols.protocol:set("JAUS/JSS")
    root:add(hf.framing, tvb(0, 1), "AS5669A")
    local ok, err = pcall(dissect_as5669a, tvb, pinfo, root)
    if not ok then root:add_proto_expert_info(ef.malformed, "dissector error: " .. tostring(err)) end
    return tvb:len()
  end
  pinfo.cols.protocol:set("JAUS")
  local off
  if framing == "OPC" then
    root:add(hf.framing, tvb(0, 8), "OPC")
    off = 8
  else
    root:add(hf.framing, tvb(0, 5), "JUDP")
    root:add(hf.judp_version, tvb(0, 1))
    root:add(hf.judp_compression, tvb(1, 1))
    root:add(hf.judp_flags, tvb(2, 1))
    local litem = root:add(hf.judp_length, tvb(3, 2))
    local length = tvb(3, 2):uint()
    if length ~= tvb:len() - 5 then
      litem:add_proto_expert_info(ef.header, string.format("JUDP length %d, datagram carries %d bytes", length, tvb:len() - 5))
    end
    off = 5
  end
  local ok, err = pcall(dissect_message, tvb, off, pinfo, tree, root)
  if not ok then root:add_proto_expert_info(ef.malformed, "dissector error: " .. tostring(err)) end
  return tvb:len()
end

-- On other ports: a prefix and at least a header after it (for AS5669A, a
-- whole transport message with message type 0 and no header compression).
local function heuristic(tvb, pinfo, tree)
  local framing = framing_of(tvb)
  if framing == "AS5669A" then
    if tvb:len() < 15 or tvb(1, 1):uint() ~= 0 then return false end
    local size = tvb(2, 2):le_uint()
    if size < 14 or size > tvb:len() - 1 then return false end
  elseif framing == nil or tvb:len() < (framing == "OPC" and 8 or 5) + 16 then
    return false
  end
  jaus.dissector(tvb, pinfo, tree)
  return true
end
