// jaus-console's page: the WebSocket protocol of docs/console.md ("Protocol"),
// no framework, nothing fetched but this file's own server.
"use strict";

(() => {
  // What is shown of a component, by its ID ({"33": ["drive", "emergency"], ...}),
  // as the server's welcome gives them from the kinds it knows: the page
  // picks its default targets by view and names no kind and no ID.
  const VIEWS = {};
  const DRIVE_PERIOD_MS = 50;      // the protocol: drive frames every 50 ms while held
  const TRACK_POINTS = 3000;       // the map's track, oldest dropped first
  const LOG_ENTRIES = 400;
  const GAMEPAD_DEADZONE = 0.12;

  const $ = (id) => document.getElementById(id);
  const componentId = (address) => Number(String(address).split(".")[2]);
  const showsAny = (address, views) => views.some((v) => (VIEWS[componentId(address)] || []).includes(v));

  // Everything the page knows; window.jausConsole exposes it to tests and to curious operators.
  const state = {
    self: null, page: null, deadmanMs: 250,
    components: new Map(),   // address -> {address, name, state, controller, authority, node, subsystem}
    control: new Map(),      // target -> {state, why}
    driving: new Map(),      // target -> {sending, by}
    emergency: new Map(),    // target -> {active, holders}
    pose: new Map(),         // source -> {x, y, yaw_rad, latitude, longitude}
    velocity: new Map(),     // source -> {vx_mps, vy_mps, yaw_rate_rps}
    track: [],               // [{x, y}] of the selected pose source
    image: null,             // {source, frame, format}
    arm: new Map(),          // source -> joints
    waypoints: [],           // [{x, y}]
    link: { open: false, peers: 0, last_heard_ms: null },
    drive: { held: false, linear: 0, angular: 0, sent: 0 },
  };

  // ---------------------------------------------------------------- socket
  let socket = null;
  let reconnectDelayMs = 500;
  let reconnectTimer = null;

  function socketUrl() {
    const scheme = location.protocol === "https:" ? "wss:" : "ws:";
    const token = new URLSearchParams(location.search).get("token");
    return `${scheme}//${location.host}/ws` + (token ? `?token=${encodeURIComponent(token)}` : "");
  }

  function connect() {
    reconnectTimer = null;
    setLink("connecting", "warn");
    let ws;
    try {
      ws = new WebSocket(socketUrl());
    } catch (e) {
      scheduleReconnect();
      return;
    }
    socket = ws;
    ws.onopen = () => {
      reconnectDelayMs = 500;
      state.link.open = true;
      setLink("connected", "ok");
      log("info", "connected to the console");
      watchCameraIfWanted();
    };
    ws.onmessage = (event) => {
      let message;
      try {
        message = JSON.parse(event.data);
      } catch (e) {
        log("error", "unreadable frame from the console");
        return;
      }
      handle(message);
    };
    ws.onclose = () => {
      if (socket !== ws) return;
      socket = null;
      state.link.open = false;
      // The server stops the drive itself when the socket closes; the page stops offering it.
      releaseAllInputs("link lost");
      log("warn", "lost the console: reconnecting");
      scheduleReconnect();
    };
    ws.onerror = () => {};  // onclose follows and says it
  }

  function scheduleReconnect() {
    if (reconnectTimer) return;
    const delay = reconnectDelayMs * (0.8 + 0.4 * Math.random());
    reconnectDelayMs = Math.min(reconnectDelayMs * 2, 8000);
    setLink(`reconnecting in ${(delay / 1000).toFixed(1)} s`, "bad");
    reconnectTimer = setTimeout(connect, delay);
  }

  function send(message) {
    if (!socket || socket.readyState !== WebSocket.OPEN) return false;
    socket.send(JSON.stringify(message));
    return true;
  }

  function setLink(text, level) {
    const el = $("link-status");
    el.textContent = text;
    el.className = "badge " + level;
  }

  // ---------------------------------------------------------------- incoming
  const handlers = {
    welcome(m) {
      Object.assign(VIEWS, m.views || {});
      state.self = m.self;
      state.page = m.page ?? null;
      if (m.deadman_ms) state.deadmanMs = m.deadman_ms;
      $("self-id").textContent = `OCU ${m.self}`;
      $("self-id").title = `this console's JAUS ID` + (m.version ? ` (jaus-console ${m.version})` : "");
    },
    tree(m) {
      state.components.clear();
      for (const s of m.subsystems || [])
        for (const n of s.nodes || [])
          for (const c of n.components || [])
            state.components.set(c.address, { ...c, node: n, subsystem: s });
      renderTree(m);
      refreshTargets();
      renderControl();
    },
    control(m) {
      const before = state.control.get(m.target);
      state.control.set(m.target, { state: m.state, why: m.why || "" });
      if (!before || before.state !== m.state)
        log(m.state === "refused" || m.state === "lost" ? "warn" : "info",
            `control of ${m.target}: ${m.state}` + (m.why ? ` (${m.why})` : ""));
      renderControl();
    },
    driving(m) {
      state.driving.set(m.target, { sending: !!m.sending, by: m.by ?? null });
      renderDriving();
    },
    pose(m) {
      // The map follows a source that reports: the first one heard unless the operator chose one.
      if (!poseSource() || (!state.pose.has(poseSource()) && !$("pose-source").dataset.touched))
        selectDefault("pose-source", m.source);
      state.pose.set(m.source, m);
      if (m.source === poseSource()) {
        const last = state.track[state.track.length - 1];
        if (!last || Math.hypot(last.x - m.x, last.y - m.y) > 0.01) {
          state.track.push({ x: m.x, y: m.y });
          if (state.track.length > TRACK_POINTS) state.track.shift();
        }
        renderPose();
      }
    },
    velocity(m) {
      state.velocity.set(m.source, m);
      $("vel-x").textContent = fixed(m.vx_mps, 2);
      $("vel-y").textContent = fixed(m.vy_mps, 2);
      $("vel-yaw").textContent = fixed(m.yaw_rate_rps * 180 / Math.PI, 1);
    },
    image(m) {
      if (m.source !== $("camera-target").value && $("camera-target").value) return;
      state.image = { source: m.source, frame: m.frame, format: m.format };
      const img = $("camera-image");
      img.src = `data:image/${m.format};base64,${m.data}`;
      img.dataset.frame = String(m.frame);
      $("camera-frame").textContent = `frame ${m.frame} · ${m.format}`;
    },
    arm(m) {
      state.arm.set(m.source, m.joints || []);
      if (!$("arm-target").value) selectDefault("arm-target", m.source);
      if (m.source === $("arm-target").value) renderArm(m.joints || []);
    },
    emergency(m) {
      const before = state.emergency.get(m.target);
      state.emergency.set(m.target, { active: !!m.active, holders: m.holders || [] });
      if (!before || before.active !== !!m.active)
        log(m.active ? "error" : "info", `emergency ${m.active ? "SET" : "cleared"} on ${m.target}` +
            (m.holders && m.holders.length ? ` (held by ${m.holders.join(", ")})` : ""));
      renderEmergency();
    },
    event(m) {
      log(m.level || "info", m.text, m.time);
    },
    link(m) {
      state.link.peers = m.peers;
      state.link.last_heard_ms = m.last_heard_ms;
      const el = $("jaus-link");
      const stale = m.last_heard_ms == null || m.last_heard_ms > 3000;
      el.textContent = `JAUS ${m.peers} peer${m.peers === 1 ? "" : "s"}` +
        (m.last_heard_ms == null ? "" : ` · ${formatAge(m.last_heard_ms)}`);
      el.className = "badge " + (m.peers === 0 || stale ? "bad" : "ok");
    },
    error(m) {
      log("error", "console refused a frame: " + m.text);
    },
  };

  function handle(message) {
    const handler = handlers[message.type];
    if (handler) handler(message);
  }

  // ---------------------------------------------------------------- tree and targets
  function renderTree(m) {
    const root = $("tree");
    root.textContent = "";
    const subsystems = m.subsystems || [];
    if (subsystems.length === 0) {
      root.append(el("p", "empty", "no subsystem heard yet"));
      return;
    }
    const top = el("ul");
    for (const s of subsystems) {
      const sItem = el("li", "subsystem");
      sItem.append(el("div", "label", `subsystem ${s.id}` + (s.name ? ` · ${s.name}` : "")));
      const nodes = el("ul");
      for (const n of s.nodes || []) {
        const nItem = el("li", "node");
        nItem.append(el("div", "label", `node ${n.id}` + (n.name ? ` · ${n.name}` : "")));
        const comps = el("ul");
        for (const c of n.components || []) {
          const row = el("li", "component");
          row.setAttribute("role", "treeitem");
          row.dataset.address = c.address;
          row.tabIndex = -1;
          if (c.address === $("control-target").value) row.classList.add("selected");
          row.append(el("span", "address", c.address), el("span", "name", c.name || ""));
          if (c.state) row.append(el("span", "state " + c.state, c.state));
          if (c.controller) {
            const mine = c.controller === state.self;
            row.append(el("span", "controller" + (mine ? " mine" : ""),
                          `⚑ ${mine ? "this console" : c.controller}` + (c.authority != null ? ` @${c.authority}` : "")));
          }
          row.addEventListener("click", () => {
            $("control-target").value = c.address;
            renderControl();
            renderTree(m);
          });
          comps.append(row);
        }
        nItem.append(comps);
        nodes.append(nItem);
      }
      sItem.append(nodes);
      top.append(sItem);
    }
    root.append(top);
  }

  // Fills each target selector with the components that show its views,
  // keeping the operator's choice, else the first one.
  function refreshTargets() {
    const all = [...state.components.values()];
    const fill = (id, views, allowAll) => {
      const select = $(id);
      const previous = select.value;
      const options = views ? all.filter((c) => showsAny(c.address, views)) : all;
      select.textContent = "";
      if (allowAll) select.append(new Option("all (every component)", "all"));
      for (const c of options) select.append(new Option(`${c.address} ${c.name || ""}`, c.address));
      if ([...select.options].some((o) => o.value === previous)) select.value = previous;
      else if (options.length) select.value = options[0].address;
    };
    fill("control-target", null);
    const driver = all.find((c) => showsAny(c.address, ["drive"]));
    if (driver && !$("control-target").dataset.touched && $("control-target").value !== driver.address)
      $("control-target").value = driver.address;
    fill("drive-target", ["drive"]);
    fill("pose-source", ["local_pose", "global_pose"]);
    fill("camera-target", ["camera"]);
    fill("arm-target", ["arm"]);
    fill("waypoint-target", ["waypoints"]);
    // The emergency button stops the vehicle (its driver) unless the operator chose otherwise.
    const emergencyTarget = $("emergency-target");
    fill("emergency-target", ["emergency"], true);
    const stops = all.find((c) => showsAny(c.address, ["emergency"]));
    if (!emergencyTarget.dataset.touched && stops) emergencyTarget.value = stops.address;
  }

  function selectDefault(id, value) {
    const select = $(id);
    if (![...select.options].some((o) => o.value === value)) select.append(new Option(value, value));
    select.value = value;
  }

  function poseSource() { return $("pose-source").value; }

  // ---------------------------------------------------------------- control
  function renderControl() {
    const target = $("control-target").value;
    const c = state.components.get(target);
    const control = state.control.get(target);
    const badge = $("control-state");
    let text = "no control", level = "";
    if (c && c.controller && c.controller === state.self) { text = "held by this console"; level = "ok"; }
    else if (c && c.controller) { text = `held by ${c.controller}`; level = "warn"; }
    if (control && control.state === "requesting") { text = "requesting…"; level = "warn"; }
    if (control && (control.state === "refused" || control.state === "lost") &&
        !(c && c.controller === state.self)) { text = control.state; level = "bad"; }
    if (control && control.state === "held") { text = "held by this console"; level = "ok"; }
    if (c && (c.state === "emergency" || c.state === "failure")) level = "bad";  // held, but it will not move
    badge.textContent = text + (c && c.state ? ` · ${c.state}` : "");
    badge.className = "badge " + level;
    badge.dataset.state = control ? control.state : "none";
    $("control-why").textContent = control && control.why ? control.why : "";
  }

  function renderDriving() {
    const target = $("drive-target").value;
    const d = state.driving.get(target);
    const el = $("driving-status");
    if (!d || !d.sending) {
      el.textContent = "not driving";
      el.className = "badge";
    } else {
      const me = d.by != null && d.by === state.page;
      el.textContent = me ? "driving (this page)" : `driving (${d.by ?? "another page"})`;
      el.className = "badge " + (me ? "ok" : "warn");
    }
    el.dataset.sending = d && d.sending ? "true" : "false";
  }

  // ---------------------------------------------------------------- emergency
  function renderEmergency() {
    const active = [...state.emergency.entries()].filter(([, e]) => e.active);
    const holders = [...new Set(active.flatMap(([, e]) => e.holders))];
    const el = $("emergency-holders");
    el.textContent = active.length
      ? `EMERGENCY on ${active.map(([t]) => t).join(", ")}` + (holders.length ? ` · held by ${holders.join(", ")}` : "")
      : "no emergency";
    el.classList.toggle("active", active.length > 0);
    $("emergency").classList.toggle("active", active.length > 0);
    $("emergency").dataset.active = active.length ? "true" : "false";
  }

  function setEmergency() {
    const target = $("emergency-target").value || "all";
    releaseAllInputs("emergency");
    if (!send({ type: "emergency", target, action: "set" }))
      log("error", "emergency NOT sent: no link to the console; use the vehicle's own stop");
  }

  // ---------------------------------------------------------------- drive: inputs and the deadman
  const keys = new Set();          // drive keys held now
  const stick = { active: false, x: 0, y: 0, pointer: null };
  const pad = { held: false, x: 0, y: 0, name: null };
  let driveTimer = null;

  const DRIVE_KEYS = {
    ArrowUp: "forward", KeyW: "forward", ArrowDown: "back", KeyS: "back",
    ArrowLeft: "left", KeyA: "left", ArrowRight: "right", KeyD: "right",
  };

  // Where typing must stay typing (numbers, selects); range sliders keep arrows only for WASD-less keys.
  function typingTarget(target) {
    if (!target || !target.tagName) return false;
    const tag = target.tagName;
    if (tag === "SELECT" || tag === "TEXTAREA") return true;
    if (tag === "INPUT") return target.type !== "range" && target.type !== "button";
    return false;
  }

  function command() {
    const limit = Number($("speed-limit").value) / 100;
    let linear = 0, angular = 0;
    if (keys.size) {
      const has = (what) => [...keys].some((k) => DRIVE_KEYS[k] === what);
      linear = (has("forward") ? 1 : 0) - (has("back") ? 1 : 0);
      angular = (has("right") ? 1 : 0) - (has("left") ? 1 : 0);
    } else if (stick.active) {
      linear = -stick.y;
      angular = stick.x;
    } else if (pad.held) {
      linear = -pad.y;
      angular = pad.x;
    }
    const held = keys.size > 0 || stick.active || pad.held;
    // Percent of effort after the speed limit; angular positive turns right (JAUS z down).
    return { held, linear: Math.round(linear * limit * 100), angular: Math.round(angular * limit * 100) };
  }

  // Whether this console drives `target` now: it holds control (the control frame, or the tree's controller).
  function controlled(target) {
    const control = state.control.get(target);
    const c = state.components.get(target);
    return (control && control.state === "held") || (!!c && !!state.self && c.controller === state.self);
  }

  let warnedNoControl = false;
  function sendDrive(c) {
    const target = $("drive-target").value;
    if (!target) return;
    if (c.held && !controlled(target)) {
      // Not ours to drive: say so once per press rather than have the console refuse 20 frames a second.
      if (!warnedNoControl) log("warn", `take control of ${target} before driving (Request control)`);
      warnedNoControl = true;
      return;
    }
    if (!c.held) warnedNoControl = false;
    if (send({ type: "drive", target, linear: c.linear, angular: c.angular, held: c.held })) state.drive.sent++;
  }

  // Called on every input change: starts the 50 ms frames on hold, sends held:false at once on release.
  function updateDrive() {
    const c = command();
    const was = state.drive.held;
    state.drive.held = c.held;
    state.drive.linear = c.held ? c.linear : 0;
    state.drive.angular = c.held ? c.angular : 0;
    if (c.held) {
      sendDrive(c);
      if (!driveTimer) driveTimer = setInterval(() => { pollGamepad(); const now = command();
        if (now.held) sendDrive(now); else updateDrive(); }, DRIVE_PERIOD_MS);
    } else {
      if (driveTimer) { clearInterval(driveTimer); driveTimer = null; }
      if (was) sendDrive({ held: false, linear: 0, angular: 0 });
      warnedNoControl = false;
    }
    renderDeadman();
  }

  function releaseAllInputs(why) {
    const was = state.drive.held;
    keys.clear();
    stick.active = false;
    pad.held = false;
    moveKnob(0, 0);
    updateDrive();
    if (was) log("info", `drive released: ${why}`);
  }

  function renderDeadman() {
    const el = $("deadman");
    const d = state.drive;
    el.textContent = d.held ? `HELD: driving at ${d.linear} % / ${d.angular} %` : "released: not driving";
    el.classList.toggle("held", d.held);
    $("stick").classList.toggle("held", stick.active);
    $("drive-linear").textContent = d.linear;
    $("drive-angular").textContent = d.angular;
  }

  window.addEventListener("keydown", (e) => {
    if (e.code === "Space" && !typingTarget(e.target)) {
      e.preventDefault();  // not a click on the focused button
      if (!e.repeat) setEmergency();
      return;
    }
    if (e.code === "Escape") { releaseAllInputs("Escape"); return; }
    if (!(e.code in DRIVE_KEYS) || typingTarget(e.target) || e.ctrlKey || e.altKey || e.metaKey) return;
    if (e.target && e.target.type === "range" && e.code.startsWith("Arrow")) return;  // the slider's own keys
    e.preventDefault();
    if (!keys.has(e.code)) { keys.add(e.code); updateDrive(); }
  });
  window.addEventListener("keyup", (e) => {
    if (e.code === "Space" && !typingTarget(e.target)) { e.preventDefault(); return; }
    if (keys.delete(e.code)) { e.preventDefault(); updateDrive(); }
  });
  // Losing the page in any way stops the drive at once (the server's deadman is the backstop).
  window.addEventListener("blur", () => releaseAllInputs("window lost focus"));
  document.addEventListener("visibilitychange", () => { if (document.hidden) releaseAllInputs("page hidden"); });
  window.addEventListener("pagehide", () => releaseAllInputs("page closed"));

  // On-screen stick (pointer events: mouse, pen, touch alike).
  const stickEl = $("stick");
  function moveKnob(x, y) {
    const r = stickEl.clientWidth / 2 - 22;
    $("stick-knob").style.transform = `translate(${x * r}px, ${y * r}px)`;
  }
  function stickFrom(e) {
    const box = stickEl.getBoundingClientRect();
    const r = box.width / 2;
    let x = (e.clientX - box.left - r) / r, y = (e.clientY - box.top - r) / r;
    const m = Math.hypot(x, y);
    if (m > 1) { x /= m; y /= m; }
    stick.x = x; stick.y = y;
    moveKnob(x, y);
  }
  stickEl.addEventListener("pointerdown", (e) => {
    stickEl.setPointerCapture(e.pointerId);
    stick.active = true;
    stick.pointer = e.pointerId;
    stickFrom(e);
    updateDrive();
  });
  stickEl.addEventListener("pointermove", (e) => {
    if (!stick.active || e.pointerId !== stick.pointer) return;
    stickFrom(e);
    updateDrive();
  });
  for (const type of ["pointerup", "pointercancel", "lostpointercapture"])
    stickEl.addEventListener(type, (e) => {
      if (!stick.active || e.pointerId !== stick.pointer) return;
      stick.active = false;
      moveKnob(0, 0);
      updateDrive();
    });

  // Gamepad: drives while a shoulder button (the deadman) is held, with the left stick.
  function pollGamepad() {
    const pads = navigator.getGamepads ? navigator.getGamepads() : [];
    const gp = [...pads].find((p) => p && p.connected);
    const status = $("gamepad-status");
    if (!gp) {
      if (pad.name) { pad.name = null; status.textContent = "no gamepad"; }
      if (pad.held) { pad.held = false; return true; }
      return false;
    }
    pad.name = gp.id;
    const shoulder = [4, 5].some((i) => gp.buttons[i] && gp.buttons[i].pressed);
    const dz = (v) => (Math.abs(v) < GAMEPAD_DEADZONE ? 0 : v);
    const was = pad.held;
    pad.x = dz(gp.axes[0] || 0);
    pad.y = dz(gp.axes[1] || 0);
    pad.held = shoulder;
    status.textContent = `gamepad: ${gp.id.slice(0, 40)} · ${shoulder ? "deadman held" : "hold a shoulder button to drive"}`;
    return was !== pad.held;
  }
  window.addEventListener("gamepadconnected", (e) => log("info", `gamepad connected: ${e.gamepad.id}`));
  window.addEventListener("gamepaddisconnected", () => { pad.held = false; updateDrive(); log("warn", "gamepad disconnected"); });
  setInterval(() => { if (!driveTimer && pollGamepad()) updateDrive(); }, 100);

  $("speed-limit").addEventListener("input", () => {
    $("speed-limit-value").textContent = `${$("speed-limit").value} %`;
    if (state.drive.held) updateDrive();
  });
  $("drive-target").addEventListener("change", () => { releaseAllInputs("driver changed"); renderDriving(); });

  // ---------------------------------------------------------------- control buttons
  $("control-target").addEventListener("change", () => {
    $("control-target").dataset.touched = "1";
    renderControl();
  });
  $("control-request").addEventListener("click", () => {
    const target = $("control-target").value;
    const authority = Math.max(0, Math.min(255, Number($("authority").value) || 0));
    if (target) send({ type: "control", target, action: "request", authority });
  });
  $("control-release").addEventListener("click", () => {
    const target = $("control-target").value;
    if (target) send({ type: "control", target, action: "release" });
  });
  $("state-resume").addEventListener("click", () => {
    const target = $("control-target").value;
    if (target) send({ type: "state", target, action: "resume" });
  });
  $("state-standby").addEventListener("click", () => {
    const target = $("control-target").value;
    if (target) send({ type: "state", target, action: "standby" });
  });
  $("emergency").addEventListener("click", setEmergency);
  $("emergency-target").addEventListener("change", () => { $("emergency-target").dataset.touched = "1"; });
  $("emergency-clear").addEventListener("click", () => {
    const target = $("emergency-target").value || "all";
    send({ type: "emergency", target, action: "clear" });
  });

  // ---------------------------------------------------------------- map
  const map = $("map");
  let view = { cx: 0, cy: 0, scale: 20 };  // metres at the centre, pixels per metre

  function renderPose() {
    const p = state.pose.get(poseSource());
    if (p) {
      $("pose-x").textContent = fixed(p.x, 2);
      $("pose-y").textContent = fixed(p.y, 2);
      $("pose-heading").textContent = fixed(((p.yaw_rad * 180 / Math.PI) % 360 + 360) % 360, 1);
      $("pose-latlon").textContent = p.latitude != null && p.longitude != null
        ? `${p.latitude.toFixed(6)}, ${p.longitude.toFixed(6)}` : "–";
      map.dataset.x = String(p.x);
      map.dataset.y = String(p.y);
    }
    drawMap();
  }

  // The view keeps the vehicle, its track and the waypoints in frame (north up, east right).
  function fitView() {
    const points = [...state.track, ...state.waypoints];
    const p = state.pose.get(poseSource());
    if (p) points.push({ x: p.x, y: p.y });
    if (!points.length) return;
    let minX = Infinity, maxX = -Infinity, minY = Infinity, maxY = -Infinity;
    for (const q of points) {
      minX = Math.min(minX, q.x); maxX = Math.max(maxX, q.x);
      minY = Math.min(minY, q.y); maxY = Math.max(maxY, q.y);
    }
    const spanNorth = Math.max(maxX - minX, 4), spanEast = Math.max(maxY - minY, 4);
    const scale = Math.min(map.width / (spanEast * 1.3), map.height / (spanNorth * 1.3));
    view = { cx: (minX + maxX) / 2, cy: (minY + maxY) / 2, scale: Math.min(scale, 80) };
  }
  const toScreen = (x, y) => [map.width / 2 + (y - view.cy) * view.scale, map.height / 2 - (x - view.cx) * view.scale];
  const fromScreen = (sx, sy) => ({ x: view.cx - (sy - map.height / 2) / view.scale,
                                    y: view.cy + (sx - map.width / 2) / view.scale });

  function niceLength(metres) {
    const p = Math.pow(10, Math.floor(Math.log10(metres)));
    for (const m of [1, 2, 5, 10]) if (m * p >= metres) return m * p;
    return 10 * p;
  }

  function drawMap() {
    fitView();
    const g = map.getContext("2d");
    g.fillStyle = "#0c1116";
    g.fillRect(0, 0, map.width, map.height);
    // Grid every scale-bar length.
    const step = niceLength(80 / view.scale);
    g.strokeStyle = "#1b252e";
    g.lineWidth = 1;
    const topLeft = fromScreen(0, 0), bottomRight = fromScreen(map.width, map.height);
    for (let e = Math.floor(topLeft.y / step) * step; e <= bottomRight.y; e += step) {
      const [sx] = toScreen(0, e);
      g.beginPath(); g.moveTo(sx, 0); g.lineTo(sx, map.height); g.stroke();
    }
    for (let n = Math.floor(bottomRight.x / step) * step; n <= topLeft.x; n += step) {
      const [, sy] = toScreen(n, 0);
      g.beginPath(); g.moveTo(0, sy); g.lineTo(map.width, sy); g.stroke();
    }
    // Origin of the local frame.
    const [ox, oy] = toScreen(0, 0);
    g.strokeStyle = "#33414d";
    g.beginPath(); g.moveTo(ox - 6, oy); g.lineTo(ox + 6, oy); g.moveTo(ox, oy - 6); g.lineTo(ox, oy + 6); g.stroke();
    // Track.
    if (state.track.length > 1) {
      g.strokeStyle = "#58a6ff";
      g.lineWidth = 2;
      g.beginPath();
      state.track.forEach((q, i) => { const [sx, sy] = toScreen(q.x, q.y); i ? g.lineTo(sx, sy) : g.moveTo(sx, sy); });
      g.stroke();
    }
    // Waypoints.
    g.fillStyle = "#d29922";
    g.strokeStyle = "#d29922";
    g.lineWidth = 1;
    g.font = "11px sans-serif";
    state.waypoints.forEach((w, i) => {
      const [sx, sy] = toScreen(w.x, w.y);
      g.beginPath(); g.arc(sx, sy, 4, 0, 2 * Math.PI); g.fill();
      g.fillText(String(i + 1), sx + 6, sy - 6);
    });
    // The vehicle and its heading (yaw from north, clockwise).
    const p = state.pose.get(poseSource());
    if (p) {
      const [sx, sy] = toScreen(p.x, p.y);
      g.save();
      g.translate(sx, sy);
      g.rotate(p.yaw_rad);
      g.fillStyle = "#3fb950";
      g.strokeStyle = "#b7f5c2";
      g.beginPath(); g.moveTo(0, -12); g.lineTo(8, 9); g.lineTo(0, 5); g.lineTo(-8, 9); g.closePath();
      g.fill(); g.stroke();
      g.restore();
    }
    // Scale bar and north.
    const bar = niceLength(100 / view.scale);
    const px = bar * view.scale;
    g.strokeStyle = "#e3e8ee"; g.fillStyle = "#e3e8ee"; g.lineWidth = 2;
    g.beginPath(); g.moveTo(12, map.height - 14); g.lineTo(12 + px, map.height - 14);
    g.moveTo(12, map.height - 19); g.lineTo(12, map.height - 9);
    g.moveTo(12 + px, map.height - 19); g.lineTo(12 + px, map.height - 9); g.stroke();
    g.font = "12px sans-serif";
    g.fillText(bar >= 1 ? `${bar} m` : `${Math.round(bar * 100)} cm`, 16 + px, map.height - 10);
    g.fillText("N ↑", map.width - 34, 18);
  }

  map.addEventListener("click", (e) => {
    const box = map.getBoundingClientRect();
    const sx = (e.clientX - box.left) * (map.width / box.width);
    const sy = (e.clientY - box.top) * (map.height / box.height);
    const w = fromScreen(sx, sy);
    state.waypoints.push({ x: Math.round(w.x * 100) / 100, y: Math.round(w.y * 100) / 100 });
    renderWaypoints();
    drawMap();
  });
  $("pose-source").addEventListener("change", () => {
    $("pose-source").dataset.touched = "1";
    state.track = [];
    renderPose();
  });
  $("map-clear-track").addEventListener("click", () => { state.track = []; drawMap(); });

  // ---------------------------------------------------------------- waypoints
  function renderWaypoints() {
    const list = $("waypoint-list");
    list.textContent = "";
    for (const w of state.waypoints) list.append(el("li", "", `x ${fixed(w.x, 2)}  y ${fixed(w.y, 2)}`));
  }
  $("waypoints-load").addEventListener("click", () => {
    const target = $("waypoint-target").value;
    if (!target) return log("warn", "no local waypoint driver in the system");
    if (!state.waypoints.length) return log("warn", "no waypoints: click the map to add some");
    send({ type: "waypoints", target, points: state.waypoints, speed_mps: Number($("waypoint-speed").value) });
  });
  $("waypoints-resume").addEventListener("click", () => {
    const target = $("waypoint-target").value;
    if (target) send({ type: "state", target, action: "resume" });
  });
  $("waypoints-clear").addEventListener("click", () => { state.waypoints = []; renderWaypoints(); drawMap(); });

  // ---------------------------------------------------------------- camera
  let cameraWanted = false;
  let cameraWatched = "";
  function watchCameraIfWanted() {
    const target = $("camera-target").value;
    if (cameraWanted && target) {
      send({ type: "camera", target, watch: true });
      cameraWatched = target;
    }
  }
  $("camera-watch").addEventListener("click", () => {
    cameraWanted = !cameraWanted;
    $("camera-watch").setAttribute("aria-pressed", String(cameraWanted));
    $("camera-watch").textContent = cameraWanted ? "Stop watching" : "Watch";
    const target = $("camera-target").value;
    if (!target) return;
    if (cameraWanted) watchCameraIfWanted();
    else { send({ type: "camera", target, watch: false }); cameraWatched = ""; }
  });
  $("camera-target").addEventListener("change", () => {
    if (cameraWatched) send({ type: "camera", target: cameraWatched, watch: false });
    cameraWatched = "";
    watchCameraIfWanted();
  });
  let panTiltTimer = null;
  function sendPanTilt() {
    panTiltTimer = null;
    const target = $("camera-target").value;
    if (target) send({ type: "camera", target, watch: cameraWanted,
                       pan_deg: Number($("camera-pan").value), tilt_deg: Number($("camera-tilt").value) });
  }
  for (const id of ["camera-pan", "camera-tilt"])
    $(id).addEventListener("input", () => {
      $(id + "-value").textContent = `${$(id).value}°`;
      if (!panTiltTimer) panTiltTimer = setTimeout(sendPanTilt, 150);  // at most ~7 commands a second
    });

  // ---------------------------------------------------------------- arm
  let armTimer = null;
  let armDragging = false;
  function renderArm(joints) {
    const box = $("arm-joints");
    const sliders = box.querySelectorAll("input[type=range]");
    if (sliders.length !== joints.length) {
      box.textContent = "";
      joints.forEach((j, i) => {
        const row = el("div", "joint");
        const label = el("label", "", `joint ${i + 1}`);
        const slider = document.createElement("input");
        slider.type = "range";
        slider.id = `arm-joint-${i}`;
        label.htmlFor = slider.id;
        slider.min = j.min; slider.max = j.max;
        slider.step = j.unit === "m" ? 0.001 : 0.5;
        slider.value = j.position;
        slider.addEventListener("pointerdown", () => { armDragging = true; });
        slider.addEventListener("pointerup", () => { armDragging = false; });
        slider.addEventListener("input", () => { if (!armTimer) armTimer = setTimeout(sendArm, 100); });
        const out = document.createElement("output");
        out.id = `arm-joint-${i}-value`;
        row.append(label, slider, out);
        box.append(row);
      });
    }
    joints.forEach((j, i) => {
      const slider = $(`arm-joint-${i}`);
      if (!armDragging && document.activeElement !== slider && !armTimer) slider.value = j.position;
      $(`arm-joint-${i}-value`).textContent = `${fixed(j.position, j.unit === "m" ? 3 : 1)} ${j.unit || ""}`;
    });
  }
  function sendArm() {
    armTimer = null;
    const target = $("arm-target").value;
    const joints = [...$("arm-joints").querySelectorAll("input[type=range]")].map((s) => Number(s.value));
    if (target && joints.length) send({ type: "arm", target, joints });
  }
  $("arm-target").addEventListener("change", () => {
    $("arm-joints").textContent = "";
    const joints = state.arm.get($("arm-target").value);
    if (joints) renderArm(joints);
  });

  // ---------------------------------------------------------------- event log and helpers
  function log(level, text, time) {
    const list = $("event-log");
    // A repeat of the newest entry counts up rather than scrolling the log away.
    const newest = list.firstElementChild;
    if (newest && newest.dataset.text === text && newest.classList.contains(level || "info")) {
      const times = Number(newest.dataset.times || 1) + 1;
      newest.dataset.times = String(times);
      newest.querySelector(".times").textContent = ` ×${times}`;
      return;
    }
    const item = el("li", level || "info");
    item.dataset.text = text;
    const when = time ? new Date(time) : new Date();
    const stamp = el("time", "", isNaN(when) ? String(time) : when.toLocaleTimeString([], { hour12: false }));
    item.append(stamp, document.createTextNode(text), el("span", "times", ""));
    list.prepend(item);
    while (list.children.length > LOG_ENTRIES) list.lastChild.remove();
  }
  function el(tag, cls, text) {
    const e = document.createElement(tag);
    if (cls) e.className = cls;
    if (text != null) e.textContent = text;
    return e;
  }
  function fixed(v, digits) {
    if (typeof v !== "number" || !isFinite(v)) return "–";
    const text = v.toFixed(digits);
    return Number(text) === 0 ? (0).toFixed(digits) : text;  // no "-0.0"
  }
  function formatAge(ms) { return ms < 1000 ? `${Math.round(ms)} ms` : `${(ms / 1000).toFixed(1)} s`; }

  window.jausConsole = { state, send, handle };
  renderDeadman();
  drawMap();
  connect();
})();
