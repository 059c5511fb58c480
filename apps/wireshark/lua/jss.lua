-- SAE JAUS (JSS) in the JAUS dissector: AS5669A datagrams (version byte 0x02,
-- docs/jss.md, "The bytes on the wire") and the JSS messages of JSS_MESSAGES, which the plugin
-- defines from the JSS descriptions (apps/wireshark/jss_table.cpp) before
-- jaus.lua. Runs after jaus.lua in the same block: it uses its field registry,
-- hf, ef, the body walkers (K, walk_body, need, fail) and the large data set
-- tables, and sets its dissect_as5669a. Field abbreviations: the transport
-- header under jaus.as5669a.*, messages under jaus.jss.<message>.<field path>.

local PRIORITIES = {[0] = "low", [1] = "normal", [2] = "high", [3] = "safety_critical"}
local BROADCASTS = {[0] = "none", [1] = "local", [2] = "global"}
local JSS_DATA_FLAGS = {[0] = "single", [1] = "first", [2] = "middle", [3] = "last"}
local JSS_NAMES = names_of(JSS_MESSAGES)

hf.as5669a = field("jaus.as5669a.message", "AS5669A transport message", ftypes.NONE)
hf.as5669a_version = field("jaus.as5669a.version", "AS5669A version", ftypes.UINT8)
hf.as5669a_type = field("jaus.as5669a.message_type", "Message type", ftypes.UINT8, nil, base.DEC, 0x3F)
hf.as5669a_hc = field("jaus.as5669a.hc_flags", "Header compression flags", ftypes.UINT8, nil, base.HEX, 0xC0)
hf.as5669a_size = field("jaus.as5669a.data_size", "Data size", ftypes.UINT16)
hf.as5669a_properties = field("jaus.as5669a.properties", "Properties", ftypes.UINT8, nil, base.HEX)
hf.as5669a_priority = field("jaus.as5669a.priority", "Priority", ftypes.UINT8, PRIORITIES, base.DEC, 0x03)
hf.as5669a_broadcast = field("jaus.as5669a.broadcast", "Broadcast", ftypes.UINT8, BROADCASTS, base.DEC, 0x0C)
hf.as5669a_ack_nak = field("jaus.as5669a.ack_nak", "ACK/NAK", ftypes.UINT8, ACK_NAK, base.DEC, 0x30)
hf.as5669a_data_flag = field("jaus.as5669a.data_flag", "Data flag", ftypes.UINT8, JSS_DATA_FLAGS, base.DEC, 0xC0)
hf.as5669a_destination = field("jaus.as5669a.destination", "Destination", ftypes.STRING)
hf.as5669a_source = field("jaus.as5669a.source", "Source", ftypes.STRING)
hf.as5669a_sequence = field("jaus.as5669a.sequence", "Sequence number", ftypes.UINT16)
hf.jss_message_id = field("jaus.jss.message_id", "JSS message ID", ftypes.UINT16, JSS_NAMES, base.HEX)
hf.jss_name = field("jaus.jss.name", "JSS message", ftypes.STRING)
hf.jss_body = field("jaus.jss.body", "JSS message", ftypes.NONE)
hf.jss_contents = field("jaus.jss.contents", "Contents", ftypes.BYTES)

ef.jss_header = ProtoExpert.new("jaus.as5669a.bad_header", "Bad AS5669A header", expert.group.MALFORMED,
  expert.severity.ERROR)
ef.jss_unknown = ProtoExpert.new("jaus.jss.unknown_id", "Unknown JSS message ID", expert.group.UNDECODED,
  expert.severity.WARN)
ef.jss_ack = ProtoExpert.new("jaus.as5669a.ack", "AS5669A acknowledgement", expert.group.SEQUENCE,
  expert.severity.CHAT)

-- ---- the JSS codec kinds (jaus/jss/codecs.hpp) --------------------------------

local prepare_ra_field = prepare_field
prepare_field = function(d, a, label)
  local k = d.k
  if k == "str8" then
    d.a = a
    d.f = field(a, label, ftypes.STRING)
    d.flength = field(a .. ".length", label .. " length", ftypes.UINT8)
  elseif k == "jssid" then
    d.a = a
    d.f = field(a, label, ftypes.STRING)
  elseif k == "embedded" then
    d.a = a
    d.f = field(a, label, ftypes.NONE)
    d.flength = field(a .. ".length", label .. " byte count", int_ftype(d.size, false))
    d.fhex = field(a .. ".hex", label .. " bytes", ftypes.BYTES)
  elseif k == "tagged" then
    d.a = a
    local names = {}
    for tag, alt in pairs(d.alts) do
      names[tag] = alt.n
      alt.f = field(a .. "." .. alt.n, alt.n, int_ftype(alt.s, false), nil, base.DEC)
    end
    d.ftag = field(a .. ".tag", label .. " variant", ftypes.UINT8, names, base.DEC)
  else
    prepare_ra_field(d, a, label)
  end
end

for id, m in pairs(JSS_MESSAGES) do
  m.slug = m.name:lower():gsub("[^%w]+", "_")
  m.code = id
  prepare_body(m.body, "jaus.jss." .. m.slug)
end

K.str8 = function(c, d, tree)
  if not need(c, 1, d, tree) then return false end
  local n = c.tvb(c.off, 1):uint()
  if not need(c, 1 + n, d, tree) then return false end
  local item = tree:add(d.f, c.tvb(c.off, 1 + n), n > 0 and c.tvb(c.off + 1, n):raw() or "")
  item:add(d.flength, c.tvb(c.off, 1))
  c.off = c.off + 1 + n
  return true
end

K.jssid = function(c, d, tree)
  if not need(c, 4, d, tree) then return false end
  local r = c.tvb(c.off, 4)
  tree:add(d.f, r, string.format("%d.%d.%d", r(0, 2):le_uint(), r(2, 1):uint(), r(3, 1):uint()))
  c.off = c.off + 4
  return true
end

K.tagged = function(c, d, tree)
  if not need(c, 1, d, tree) then return false end
  local tag = c.tvb(c.off, 1):uint()
  local item = tree:add(d.ftag, c.tvb(c.off, 1))
  local alt = d.alts[tag]
  if alt == nil then return fail(c, item, string.format("%s: variant tag %d is not defined", d.a, tag)) end
  if not need(c, 1 + alt.s, d, tree) then return false end
  tree:add_le(alt.f, c.tvb(c.off + 1, alt.s))
  c.off = c.off + 1 + alt.s
  return true
end

local dissect_jss_contents

-- A whole JSS message inside another (msg32: its byte count includes its ID).
K.embedded = function(c, d, tree)
  if not need(c, d.size, d, tree) then return false end
  local n = c.tvb(c.off, d.size):le_uint()
  local count = tree:add_le(d.flength, c.tvb(c.off, d.size))
  c.off = c.off + d.size
  if n < d.min then
    return fail(c, count, string.format("%s: byte count %d is below %d (the message ID)", d.a, n, d.min))
  end
  if n > c.lim - c.off then
    return fail(c, count, string.format("%s: byte count %d but %d bytes left", d.a, n, c.lim - c.off))
  end
  if n < 2 then  -- user data (list elements of a user-defined format): no message ID
    if n > 0 then tree:add(d.fhex, c.tvb(c.off, n)) else tree:add(d.fhex, "") end
  else
    local item = tree:add(d.f, c.tvb(c.off, n))
    dissect_jss_contents(c.tvb, c.off, n, item, d.fhex)
  end
  c.off = c.off + n
  return true
end

-- Contents: the u16 message ID, then its body. The message, or nil when the ID
-- is unknown (then the bytes show as `bytes_field`).
dissect_jss_contents = function(tvb, off, len, tree, bytes_field)
  if len < 2 then
    tree:add(bytes_field, tvb(off, len)):add_proto_expert_info(ef.malformed,
      string.format("%d bytes of contents: shorter than a message ID", len))
    return nil
  end
  local id = tvb(off, 2):le_uint()
  local m = JSS_MESSAGES[id]
  tree:add_le(hf.jss_message_id, tvb(off, 2))
  if m == nil then
    tree:add(bytes_field, tvb(off, len)):add_proto_expert_info(ef.jss_unknown,
      string.format("Unknown JSS message ID 0x%04X: not dissected", id))
    return nil
  end
  tree:add(hf.jss_name, tvb(off, 2), m.name):set_generated()
  tree:set_text(string.format("%s (0x%04X)", m.name, id))
  local c = {tvb = tvb, off = off + 2, lim = off + len, dialect = 0, dims = {}, values = {}, ranges = {}}
  local ok, err = pcall(walk_body, c, m.body, tree)
  if not ok then
    tree:add_proto_expert_info(ef.malformed, "dissector error: " .. tostring(err))
  elseif not c.failed and c.off < c.lim then
    tree:add_proto_expert_info(ef.trailing, string.format("%d bytes after the last field", c.lim - c.off))
  end
  return m
end

-- ---- AS5669A ------------------------------------------------------------------

local function jss_id_at(tvb, off)  -- the header's u32: component, node, subsystem (u16)
  return string.format("%d.%d.%d", tvb(off + 2, 2):le_uint(), tvb(off + 1, 1):uint(), tvb(off, 1):uint())
end

-- Large messages: by (source, destination), data flags 1 first, 2 middle, 3 last
-- (collect_packet, jaus.lua); the whole message is dissected on the last packet.
local JSS_LARGE_FLAGS = {first = 1, last = 3}

local function large_message(tvb, off, size, flag, seq, src, dst, pinfo, tree, index)
  local done_key = pinfo.number .. "/" .. index
  collect_packet("jss:" .. src .. ">" .. dst, done_key, JSS_LARGE_FLAGS, tvb, off, size, flag, seq, pinfo)
  tree:add_proto_expert_info(ef.lds, string.format("Packet of a large message (%s, sequence %d)", JSS_DATA_FLAGS[flag], seq))
  local rtvb = reassembled_tvb(done_key, tree, "Reassembled JSS message")
  if rtvb then
    local body = tree:add(hf.jss_body, rtvb())
    return dissect_jss_contents(rtvb, 0, rtvb:len(), body, hf.jss_contents)
  end
  if size > 0 then tree:add(hf.jss_contents, tvb(off, size)) end
  return nil
end

-- A transport message that cannot be read: said on its item and in the Info column.
local function bad_header(pinfo, item, index, text)
  item:add_proto_expert_info(ef.jss_header, text)
  local info = "Malformed AS5669A: " .. text
  if index == 1 then pinfo.cols.info:set(info) else pinfo.cols.info:append("; " .. info) end
  return nil
end

-- One transport message at `off`; the offset after it, or nil when the rest cannot be read.
local function dissect_transport_message(tvb, off, pinfo, root, index)
  local avail = tvb:len() - off
  if avail < 14 then
    return bad_header(pinfo, root, index, string.format("%d bytes: shorter than a transport message (14)", avail))
  end
  local size = tvb(off + 1, 2):le_uint()
  local t = root:add(hf.as5669a, tvb(off, math.min(math.max(size, 14), avail)))
  local type_item = t:add(hf.as5669a_type, tvb(off, 1))
  local hc_item = t:add(hf.as5669a_hc, tvb(off, 1))
  local size_item = t:add_le(hf.as5669a_size, tvb(off + 1, 2))
  local type_byte = tvb(off, 1):uint()
  if bit32.band(type_byte, 0xC3) ~= 0 then
    return bad_header(pinfo, hc_item, index,
      string.format("header compression flags set (0x%02X): not supported, the rest is not dissected", type_byte))
  end
  if type_byte ~= 0 then
    return bad_header(pinfo, type_item, index, string.format("message type %d: only 0 (JAUS) is defined", type_byte))
  end
  if size < 14 or size > avail then
    return bad_header(pinfo, size_item, index,
      string.format("data size %d: at least 14, at most the %d bytes left", size, avail))
  end
  local props = tvb(off + 3, 1):uint()
  local p = t:add(hf.as5669a_properties, tvb(off + 3, 1))
  p:add(hf.as5669a_priority, tvb(off + 3, 1))
  local bitem = p:add(hf.as5669a_broadcast, tvb(off + 3, 1))
  p:add(hf.as5669a_ack_nak, tvb(off + 3, 1))
  p:add(hf.as5669a_data_flag, tvb(off + 3, 1))
  if bit32.extract(props, 2, 2) == 3 then bitem:add_proto_expert_info(ef.jss_header, "broadcast flag 3 is not defined") end
  local dst, src = jss_id_at(tvb, off + 4), jss_id_at(tvb, off + 8)
  t:add(hf.as5669a_destination, tvb(off + 4, 4), dst)
  t:add(hf.as5669a_source, tvb(off + 8, 4), src)
  local n = size - 14
  local seq = tvb(off + 12 + n, 2):le_uint()
  t:add_le(hf.as5669a_sequence, tvb(off + 12 + n, 2))

  local ack_nak, flag = bit32.extract(props, 4, 2), bit32.extract(props, 6, 2)
  local what
  if n == 0 then
    what = ack_nak == 3 and "ACK" or ack_nak == 2 and "NAK" or "Empty"
    t:add_proto_expert_info(ef.jss_ack, string.format("%s, sequence %d", what, seq))
  elseif flag ~= 0 then
    local m = large_message(tvb, off + 12, n, flag, seq, src, dst, pinfo, t, index)
    what = (m and m.name or "Large message") .. string.format(" [%s, seq %d]", JSS_DATA_FLAGS[flag], seq)
  else
    local body = t:add(hf.jss_body, tvb(off + 12, n))
    local m = dissect_jss_contents(tvb, off + 12, n, body, hf.jss_contents)
    local id = n >= 2 and tvb(off + 12, 2):le_uint() or 0
    what = m and string.format("%s (0x%04X)", m.name, id) or string.format("Unknown JSS (0x%04X)", id)
  end
  if ack_nak == 1 then what = what .. " [ACK requested]" end
  t:set_text(string.format("%s, %s -> %s, seq %d", what, src, dst, seq))
  local info = string.format("%s %s -> %s", what, src, dst)
  if index == 1 then pinfo.cols.info:set(info) else pinfo.cols.info:append("; " .. info) end
  return off + size
end

dissect_as5669a = function(tvb, pinfo, root)
  root:add(hf.as5669a_version, tvb(0, 1))
  root:append_text(", AS5669A")
  local off, index = 1, 1
  while off and off < tvb:len() do
    off = dissect_transport_message(tvb, off, pinfo, root, index)
    index = index + 1
  end
  if tvb:len() == 1 then bad_header(pinfo, root, 1, "a version byte and nothing else") end
end
