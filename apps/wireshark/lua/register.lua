-- The end of the JAUS half: the protocol's fields and expert infos, all made
-- by jaus.lua and jss.lua by now (Wireshark copies the tables when they are
-- set), and its UDP port and heuristic.
jaus.fields = fields
jaus.experts = {ef.malformed, ef.unknown, ef.trailing, ef.header, ef.lds, ef.jss_header, ef.jss_unknown, ef.jss_ack}

register_udp(jaus, heuristic)
