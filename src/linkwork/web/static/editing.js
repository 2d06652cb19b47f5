// linkwork viewer: edits of dimensions and masses, typed in the panel or dragged on the scheme.
//
// Every edit goes to POST api/edit, which answers in some milliseconds with what the edit changes
// (linkwork.web.update); the page merges it and shows it at once.  The latest value wins: one edit is
// solved at a time, and a newer value replaces the one waiting to be sent, so nothing queues up.  An
// edit that fails (a value out of range, a mechanism that no longer assembles) shows linkwork's
// message and the page keeps the last mechanism that worked; a dragged value must keep the mechanism
// assembling wherever the file's does, and the message says at which crank angles it would not (drawn
// as arcs about the crank's pivot).  Once an edit is made (a drag let go, a value applied) it joins the
// history (undo, redo) and the whole cycle is solved again, its labels placed (POST api/solve).
//
// Handles on the scheme, at the crank angle shown: squares on the frame's points (and guides' points
// given by coordinates) move them; diamonds near the far end of a link given by its length slide along
// the link; rings on the points of a link given by its points move them in the link's axes; a ring at
// the end of a guide on the frame turns its axis.  Values snap to round steps (1 mm on a drawing of about
// a metre, 0.1 degree); hold Alt for none.
"use strict";

(function () {
  const V = window.linkworkViewer;
  const { $, svg, html, fmt, state, T } = V;
  const E = {
    client: Array.from(crypto.getRandomValues(new Uint8Array(9)), (b) => b.toString(16).padStart(2, "0")).join(""),
    seq: 0,
    epoch: 0, // answers to edits sent before the last return to the file's values are dropped
    inflight: null,
    pending: null,
    accepted: {}, // the overrides of the mechanism shown
    history: [{}],
    at: 0,
    drag: null,
    refine: null, // the timer or the controller of the whole cycle asked for
    handles: [],
    editable: false,
  };
  const DEG = Math.PI / 180;

  function units(m, kind) { return m.units[kind]; } // [unit, factor from SI]
  const same = (a, b) => JSON.stringify(Object.entries(a).sort()) === JSON.stringify(Object.entries(b).sort());

  // ------------------------------------------------------------------ solving, latest wins

  // ``overrides``: the whole edit (SI); drag: a dragged value (it must assemble where the file's does);
  // commit: the edit is made (history, the whole cycle placed); record: false for undo and redo
  function propose(overrides, opts) {
    E.pending = Object.assign({ overrides, drag: false, commit: false, record: true, epoch: E.epoch }, opts || {});
    pump();
  }

  async function pump() {
    if (E.inflight || !E.pending) return;
    const req = (E.inflight = E.pending);
    E.pending = null;
    req.seq = ++E.seq;
    const t0 = performance.now();
    let status = 0, body;
    try {
      const r = await fetch("api/edit", {
        method: "POST", headers: { "Content-Type": "application/json", Accept: "application/vnd.linkwork.edit, application/json" },
        body: JSON.stringify({ overrides: req.overrides, whole_turn: req.drag, client: E.client, seq: req.seq }),
      });
      status = r.status;
      if (r.ok) body = V.readEdit(await r.arrayBuffer());
      else body = await r.json().catch(() => ({ error: T("view.server_answered", { status: r.status }) }));
    } catch (err) {
      status = 0;
      body = { error: T("view.no_answer", { error: err.message || err }) };
    }
    E.inflight = null;
    pump(); // the next value is solved while this answer is drawn
    if (req.epoch !== E.epoch) return; // sent before the file's values were brought back
    if (status >= 200 && status < 300) accept(req, body, performance.now() - t0);
    else if (status !== 409) refuse(req, body);
    if (req.commit) settle(req);
  }

  function accept(req, ans, ms) {
    E.accepted = ans.overrides;
    if (req.typed) for (const input of $("params").querySelectorAll("input[data-typed]")) delete input.dataset.typed;
    V.show(V.merge(state.full, ans), true);
    V.hideError();
    trouble(null);
    $("scheme").setAttribute("data-edit-ms", ms.toFixed(1));
    const n = Object.keys(E.accepted).length;
    $("edit-status").textContent = n ? T("view.changed", { n }) : T("view.file_values");
  }

  function refuse(req, body) {
    V.showError(body.error || T("view.edit_failed"));
    trouble(body.events || null);
    if (E.drag) E.drag.handle.el.classList.add("bad");
  }

  // an edit made: into the history, and the whole cycle solved again for its labels (the file's is at hand)
  function settle(req) {
    if (req.record && !same(E.accepted, E.history[E.at])) {
      E.history = E.history.slice(0, E.at + 1);
      E.history.push(Object.assign({}, E.accepted));
      E.at += 1;
    }
    buttons();
    clearRefine();
    if (!Object.keys(E.accepted).length) {
      if (state.data !== state.base && !E.inflight && !E.pending) V.show(state.base, false);
      return;
    }
    E.refine = setTimeout(refine, 300);
  }

  function clearRefine() {
    if (E.refine && E.refine.abort) E.refine.abort();
    else if (E.refine) clearTimeout(E.refine);
    E.refine = null;
  }

  async function refine() {
    const wanted = Object.assign({}, E.accepted);
    const ctl = (E.refine = new AbortController());
    try {
      const r = await fetch("api/solve", {
        method: "POST", headers: { "Content-Type": "application/json", Accept: "application/json" },
        body: JSON.stringify({ overrides: wanted }), signal: ctl.signal,
      });
      if (!r.ok || E.drag || E.inflight || E.pending || !same(wanted, E.accepted)) return;
      const m = V.model(await r.json());
      V.show(m, false);
      V.grow(m.scene);
    } catch (err) {
      // superseded by a newer edit (aborted), or the server went away: the edit's answer stays shown
    } finally {
      if (E.refine === ctl) E.refine = null;
    }
  }

  function go(at) {
    E.at = at;
    if (Object.keys(E.history[at]).length) propose(E.history[at], { commit: true, record: false });
    else toFile({ record: false });
    buttons();
  }
  function undo() { if (E.at > 0) go(E.at - 1); }
  function redo() { if (E.at < E.history.length - 1) go(E.at + 1); }

  function buttons() {
    $("undo").disabled = !E.editable || E.at === 0;
    $("redo").disabled = !E.editable || E.at >= E.history.length - 1;
  }

  // ------------------------------------------------------------------ where a variant does not assemble

  // arcs about the crank's pivot over the crank angles where the refused variant does not assemble
  function trouble(events) {
    let g = $("trouble");
    if (!g) g = svg("g", { id: "trouble" }, $("scheme"));
    g.replaceChildren();
    const m = state.data;
    const drive = m && m.pairs.find((p) => p.driven && p.frame_point !== null);
    if (!events || !drive) return;
    const i = state.index, centre = m.positions.at(i, drive.frame_point);
    const pin = m.positions.at(i, drive.points[0] === drive.frame_point ? drive.points[1] : drive.points[0]);
    if (!centre) return;
    const r = 1000 * Math.max(pin ? Math.hypot(pin[0] - centre[0], pin[1] - centre[1]) : 0, 0.12 * m.scene.size);
    const cx = 1000 * centre[0], cy = -1000 * centre[1];
    for (const e of events.filter((x) => x.kind === "no-assembly")) {
      const a = Math.min(e.start_deg, e.end_deg) * DEG, b = Math.max(e.start_deg, e.end_deg) * DEG;
      const pt = (t) => `${(cx + r * Math.cos(t)).toFixed(3)},${(cy - r * Math.sin(t)).toFixed(3)}`;
      const sweep = Math.min(b - a, 2 * Math.PI - 1e-6);
      svg("path", {
        class: "trouble", d: `M${cx.toFixed(3)},${cy.toFixed(3)} L${pt(a)} A${r.toFixed(3)},${r.toFixed(3)} 0 ${sweep > Math.PI ? 1 : 0} 0 ${pt(a + sweep)} Z`,
        "data-from-deg": String(e.start_deg), "data-to-deg": String(e.end_deg),
      }, g);
      const mid = a + sweep / 2;
      const t = svg("text", {
        class: "trouble-label", x: (cx + 0.6 * r * Math.cos(mid)).toFixed(3), y: (cy - 0.6 * r * Math.sin(mid)).toFixed(3),
        "font-size": (0.8 * 1000 * m.scene.em).toFixed(3), "text-anchor": "middle", "dominant-baseline": "central",
      }, g);
      t.textContent = T("view.no_assembly", { start: fmt(e.start_deg, 3), end: fmt(e.end_deg, 3) });
    }
  }

  // ------------------------------------------------------------------ the panel

  function buildParams(m) {
    const root = $("params");
    root.replaceChildren();
    const note = $("edit-note");
    E.editable = m.editable && !state.embedded;
    if (state.embedded) note.textContent = T("view.exported");
    else if (!m.editable) note.textContent = T("view.not_editable");
    else note.textContent = T("view.edit_help");
    for (const id of ["apply", "reset", "save"]) $(id).disabled = !E.editable;
    buttons();
    let group = null;
    for (const p of m.parameters || []) {
      if (p.group !== group) {
        group = p.group;
        html("h3", T(`view.group.${group}`), root);
      }
      const [unit, k] = units(m, p.kind);
      const row = html("label", null, root, { class: "param" });
      html("span", p.name + (p.note ? ` (${p.note})` : ""), row, { class: "name", title: p.name });
      const input = html("input", null, row, { type: "number", step: "any", "data-param": p.name, "data-kind": p.kind });
      input.value = shown(p.value, k);
      input.defaultValue = input.value;
      input.disabled = !E.editable;
      input.addEventListener("input", () => { input.dataset.typed = "1"; row.classList.toggle("changed", input.value !== input.defaultValue); });
      html("span", unit, row);
    }
  }

  const shown = (v, k) => String(Number((v * k).toPrecision(10)));

  // the panel's values from the model shown (not those being typed)
  function syncParams(m) {
    const values = Object.fromEntries((m.parameters || []).map((p) => [p.name, p]));
    for (const input of $("params").querySelectorAll("input[data-param]")) {
      const p = values[input.getAttribute("data-param")];
      if (!p || input.dataset.typed === "1") continue;
      const text = shown(p.value, units(m, p.kind)[1]);
      if (input.value === text) continue;
      input.value = text;
      input.parentElement.classList.toggle("changed", text !== input.defaultValue);
    }
  }

  function typed() {
    const out = Object.assign({}, E.accepted);
    const bad = [];
    for (const input of $("params").querySelectorAll("input[data-param]")) {
      if (input.dataset.typed !== "1") continue;
      const v = Number(input.value);
      if (input.value.trim() === "" || !isFinite(v)) { bad.push(input.getAttribute("data-param")); continue; }
      out[input.getAttribute("data-param")] = v / units(state.data, input.getAttribute("data-kind"))[1];
    }
    return { out, bad };
  }

  function apply(ev) {
    ev.preventDefault();
    const { out, bad } = typed();
    if (bad.length) { V.showError(bad.map((b) => T("view.enter_number", { name: b })).join("\n")); return; }
    propose(out, { commit: true, typed: true });
  }

  // the file's values: the mechanism as loaded, shown at once
  function reset() {
    for (const input of $("params").querySelectorAll("input[data-param]")) {
      delete input.dataset.typed;
      input.value = input.defaultValue;
      input.parentElement.classList.remove("changed");
    }
    E.pending = null;
    toFile({ record: true });
  }

  function toFile(req) {
    E.epoch += 1;
    clearRefine();
    E.accepted = {};
    V.show(state.base, false);
    V.hideError();
    trouble(null);
    $("edit-status").textContent = T("view.file_values");
    settle(Object.assign({ record: true }, req));
  }

  async function save() {
    try {
      const r = await fetch("api/save", {
        method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify({ overrides: E.accepted }),
      });
      if (!r.ok) { V.showError((await r.json().catch(() => ({}))).error || T("view.server_answered", { status: r.status })); return; }
      const disposition = r.headers.get("Content-Disposition") || "";
      const utf8 = /filename\*=UTF-8''([^;\s]+)/.exec(disposition);  // the name in any script (RFC 6266)
      const name = utf8 ? decodeURIComponent(utf8[1])
        : (/filename="([^"]+)"/.exec(disposition) || [])[1] || "mechanism-edited.yaml";
      const url = URL.createObjectURL(await r.blob());
      const a = html("a", null, document.body, { href: url, download: name });
      a.click();
      a.remove();
      setTimeout(() => URL.revokeObjectURL(url), 1000);
      $("edit-status").textContent = T("view.saved", { name });
    } catch (err) {
      V.showError(T("view.no_answer", { error: err.message || err }));
    }
  }

  // ------------------------------------------------------------------ handles

  function value(m, name) { const p = m.parameters.find((x) => x.name === name); return p ? p.value : null; }

  // the handles a mechanism's parameters allow
  function handlesOf(m) {
    const names = new Set((m.parameters || []).map((p) => p.name));
    const out = [];
    const onFrame = (p) => m.pairs.some((q) => q.type === "revolute" && q.links.includes(0) && q.points.includes(p));
    m.points.forEach((pt, p) => {
      const [link, name] = pt.name.split(".");
      const base = pt.link === 0 ? `frame.points.${name}` : `links.${link}.points.${name}`;
      if (!names.has(base + ".x")) return;
      if (pt.link === 0) out.push({ kind: "frame", id: base, x: base + ".x", y: base + ".y", point: p, what: T("view.what.frame_point", { name }) });
      else if (!onFrame(p)) out.push({ kind: "point", id: base, x: base + ".x", y: base + ".y", point: p, link: pt.link, what: T("view.what.point", { name, link }) });
    });
    for (const link of m.links) {
      const id = `links.${link.name}.length`;
      if (link.ends && names.has(id)) out.push({ kind: "length", id, param: id, ends: link.ends, what: T("view.what.length", { link: link.name }) });
    }
    for (const pair of m.pairs) {
      if (pair.type !== "prismatic" || pair.links[0] !== 0) continue;
      const axis = `joints.${pair.joint}.axis`, through = `joints.${pair.joint}.through`;
      if (names.has(through + ".x")) out.push({ kind: "frame", id: through, x: through + ".x", y: through + ".y", pair, what: T("view.what.guide_point", { joint: pair.joint }) });
      if (names.has(axis)) out.push({ kind: "axis", id: axis, param: axis, pair, what: T("view.what.guide_axis", { joint: pair.joint }) });
    }
    return out;
  }

  // where a guide's axis turns about: its named point, or the point given by coordinates
  function pivot(m, h) {
    if (h.pair.through_point !== null) return m.local[h.pair.through_point];
    const base = `joints.${h.pair.joint}.through`;
    return [value(m, base + ".x"), value(m, base + ".y")];
  }

  // where a handle is at sample i of model m (metres), or null
  function where(m, h, i) {
    const r = m.scene.r;
    if (h.kind === "frame" && h.point !== undefined) return m.local[h.point];
    if (h.kind === "frame") return pivot(m, h);
    if (h.kind === "point") return m.positions.at(i, h.point);
    if (h.kind === "length") {
      const a = m.positions.at(i, h.ends[0]), b = m.positions.at(i, h.ends[1]);
      if (!a || !b) return null;
      const L = Math.hypot(b[0] - a[0], b[1] - a[1]) || 1, back = Math.min(2.4 * r, 0.35 * L);
      return [b[0] - (back * (b[0] - a[0])) / L, b[1] - (back * (b[1] - a[1])) / L];
    }
    const c = pivot(m, h), angle = value(m, h.param);
    const u = [Math.cos(angle), Math.sin(angle)];
    // at the end of the guide's line farther from its point
    const guide = m.scene.items.find((it) => it.kind === "guide" && it.name === h.pair.joint);
    const ends = guide ? guide.xy.map((p) => (p[0] - c[0]) * u[0] + (p[1] - c[1]) * u[1]) : [0.25 * m.scene.size];
    const far = ends.reduce((a, b) => (Math.abs(b) > Math.abs(a) ? b : a));
    const reach = far - Math.sign(far || 1) * 1.5 * r;
    return [c[0] + reach * u[0], c[1] + reach * u[1]];
  }

  function buildHandles(m) {
    let g = $("handles");
    if (!g) g = svg("g", { id: "handles" }, $("scheme"));
    g.replaceChildren();
    E.handles = E.editable ? handlesOf(m) : [];
    const r = 1000 * m.scene.r;
    for (const h of E.handles) {
      const attrs = { class: `handle ${h.kind}`, "data-handle": h.id, tabindex: "-1" };
      if (h.kind === "length") h.el = svg("rect", Object.assign(attrs, { width: (1.5 * r).toFixed(3), height: (1.5 * r).toFixed(3) }), g);
      else if (h.kind === "frame") h.el = svg("rect", Object.assign(attrs, { width: (2.4 * r).toFixed(3), height: (2.4 * r).toFixed(3) }), g);
      else h.el = svg("circle", Object.assign(attrs, { r: ((h.kind === "axis" ? 1.1 : 1.4) * r).toFixed(3) }), g);
      h.size = Number(h.el.getAttribute("width") || 0);
      svg("title", {}, h.el).textContent = T("view.drag", { what: h.what, id: h.id });
      h.el.addEventListener("pointerdown", (ev) => grab(ev, h));
    }
    const readout = svg("text", { id: "drag-readout", "font-size": (1000 * m.scene.em).toFixed(3), visibility: "hidden" }, g);
    readout.textContent = "";
    g.setAttribute("display", $("show-handles").checked ? "inline" : "none");
  }

  function placeHandles(i) {
    const m = state.data;
    for (const h of E.handles) {
      if (E.drag && E.drag.handle === h) continue;
      put(h, where(m, h, i));
    }
  }

  function put(h, xy) {
    if (!xy || !isFinite(xy[0])) { h.el.setAttribute("visibility", "hidden"); return; }
    h.el.setAttribute("visibility", "visible");
    const x = 1000 * xy[0], y = -1000 * xy[1];
    if (h.size) {
      h.el.setAttribute("x", (x - h.size / 2).toFixed(3)); h.el.setAttribute("y", (y - h.size / 2).toFixed(3));
      if (h.kind === "length") h.el.setAttribute("transform", `rotate(45 ${x.toFixed(3)} ${y.toFixed(3)})`);
    } else { h.el.setAttribute("cx", x.toFixed(3)); h.el.setAttribute("cy", y.toFixed(3)); }
  }

  // the pointer in the model's axes, m
  function pointer(ev) {
    const root = $("scheme");
    const pt = root.createSVGPoint();
    pt.x = ev.clientX; pt.y = ev.clientY;
    const p = pt.matrixTransform(root.getScreenCTM().inverse());
    return [p.x / 1000, -p.y / 1000];
  }

  function grab(ev, h) {
    if (!E.editable || ev.button !== 0 || E.drag) return;
    ev.preventDefault();
    const m = state.data, i = state.index, p = pointer(ev), at = where(m, h, i);
    if (!at || ((h.kind === "length" || h.kind === "point") && !m.valid[i])) return;
    const drag = { handle: h, model: m, base: Object.assign({}, E.accepted), p0: p, at, start: {}, last: null };
    for (const name of [h.param, h.x, h.y].filter(Boolean)) drag.start[name] = value(m, name);
    if (h.kind === "length") {
      const [a, u] = axisOf(m, h, i);
      drag.grab = drag.start[h.param] - ((p[0] - a[0]) * u[0] + (p[1] - a[1]) * u[1]);
    } else if (h.kind === "point") {
      const local = toLocal(m, h, i, p);
      drag.grab = [drag.start[h.x] - local[0], drag.start[h.y] - local[1]];
    } else if (h.kind === "axis") {
      const c = pivot(m, h);
      drag.angle0 = Math.atan2(p[1] - c[1], p[0] - c[0]);
    }
    E.drag = drag;
    clearRefine();
    h.el.setPointerCapture(ev.pointerId);
    h.el.classList.add("dragging");
    h.el.addEventListener("pointermove", move);
    h.el.addEventListener("pointerup", release);
    h.el.addEventListener("pointercancel", release);
  }

  function axisOf(m, h, i) {
    const a = m.positions.at(i, h.ends[0]), b = m.positions.at(i, h.ends[1]);
    const L = Math.hypot(b[0] - a[0], b[1] - a[1]);
    return [a, [(b[0] - a[0]) / L, (b[1] - a[1]) / L]];
  }

  function toLocal(m, h, i, p) {
    const pose = m.poses.at(i, h.link);
    const c = Math.cos(pose[2]), s = Math.sin(pose[2]), d = [p[0] - pose[0], p[1] - pose[1]];
    return [c * d[0] + s * d[1], -s * d[0] + c * d[1]];
  }

  // the values a drag to ``p`` gives, at sample i of the model the drag started from (SI)
  function dragged(drag, p, i, exact) {
    const h = drag.handle, m = drag.model, out = {};
    const lengthStep = Math.pow(10, Math.round(Math.log10(m.scene.size / 500)));
    const snap = (v, step) => (exact ? v : Number((Math.round(v / step) * step).toPrecision(12)));
    if (h.kind === "frame") {
      out[h.x] = snap(drag.start[h.x] + p[0] - drag.p0[0], lengthStep);
      out[h.y] = snap(drag.start[h.y] + p[1] - drag.p0[1], lengthStep);
    } else if (h.kind === "length") {
      if (!m.valid[i]) return null;
      const [a, u] = axisOf(m, h, i);
      out[h.param] = Math.max(snap((p[0] - a[0]) * u[0] + (p[1] - a[1]) * u[1] + drag.grab, lengthStep), lengthStep);
    } else if (h.kind === "point") {
      if (!m.valid[i]) return null;
      const local = toLocal(m, h, i, p);
      out[h.x] = snap(local[0] + drag.grab[0], lengthStep);
      out[h.y] = snap(local[1] + drag.grab[1], lengthStep);
    } else {
      const c = pivot(m, h);
      let turn = Math.atan2(p[1] - c[1], p[0] - c[0]) - drag.angle0;
      turn -= 2 * Math.PI * Math.round(turn / (2 * Math.PI));
      out[h.param] = snap(drag.start[h.param] + turn, 0.1 * DEG);
    }
    return out;
  }

  function move(ev) {
    const drag = E.drag;
    if (!drag) return;
    const p = pointer(ev);
    put(drag.handle, [drag.at[0] + p[0] - drag.p0[0], drag.at[1] + p[1] - drag.p0[1]]);
    const values = dragged(drag, p, state.index, ev.altKey);
    if (!values) return;
    readout(drag, values, p);
    const overrides = Object.assign({}, drag.base, values);
    if (drag.last && same(overrides, drag.last)) return;
    drag.last = overrides;
    propose(overrides, { drag: true });
  }

  function readout(drag, values, p) {
    const t = $("drag-readout"), m = drag.model;
    const text = Object.entries(values).map(([name, v]) => {
      const [unit, k] = units(m, name.endsWith(".axis") ? "angle" : "length");
      return `${name} = ${fmt(v * k, 6)} ${unit}`;
    });
    t.textContent = text.join(", ");
    t.setAttribute("x", (1000 * p[0] + 1000 * 2 * m.scene.r).toFixed(3));
    t.setAttribute("y", (-1000 * p[1] - 1000 * 2 * m.scene.r).toFixed(3));
    t.setAttribute("visibility", "visible");
  }

  function release(ev) {
    const drag = E.drag;
    if (!drag) return;
    const h = drag.handle;
    h.el.releasePointerCapture(ev.pointerId);
    h.el.removeEventListener("pointermove", move);
    h.el.removeEventListener("pointerup", release);
    h.el.removeEventListener("pointercancel", release);
    h.el.classList.remove("dragging", "bad");
    $("drag-readout").setAttribute("visibility", "hidden");
    E.drag = null;
    // the last value sent is the edit made (the last that assembled, where it did not)
    if (drag.last) propose(drag.last, { drag: true, commit: true });
    placeHandles(state.index);
  }

  // ------------------------------------------------------------------ the family of a synthesised file

  // a slider along the free parameter of the family the file's requirements leave (GET api/family); each
  // member is an edit of named parameters, solved and drawn as the slider moves, made when it is let go
  async function buildFamily() {
    const old = $("family");
    if (old) old.remove();
    if (!E.editable) return;
    let f;
    try {
      const r = await fetch("api/family");
      if (!r.ok) return;
      f = await r.json();
    } catch (e) { return; }
    if (!f.overrides || !f.overrides.length) return;
    const box = html("div", null, null, { id: "family", class: "param" });
    $("params").before(box);
    html("h3", T("view.family"), box);
    const text = html("span", null, box, { id: "family-text" });
    const input = html("input", null, box, { type: "range", min: 0, max: f.overrides.length - 1, step: 1,
                                             value: f.picked, id: "family-slider" });
    const say = (i) => {  // the texts, units and numbers in the page's language (family_members)
      text.textContent = `${f.parameter} ${V.fixed(f.values[i], 2)}${f.unit_shown}, ${f.quantity} ` +
        `${V.fixed(f.quantity_values[i], 2)}${f.quantity_unit_shown}`;
    };
    if (f.note) box.title = f.note;
    say(f.picked);
    input.addEventListener("input", () => { const i = Number(input.value); say(i); propose(f.overrides[i]); });
    input.addEventListener("change", () => propose(f.overrides[Number(input.value)], { commit: true }));
  }

  // ------------------------------------------------------------------ wiring

  V.on("build", (m) => {
    buildParams(m); buildHandles(m); E.accepted = {}; E.history = [{}]; E.at = 0; buttons(); buildFamily();
  });
  V.on("show", (m) => { syncParams(m); });
  V.on("index", (i) => placeHandles(i));
  $("edit-form").addEventListener("submit", apply);
  $("reset").addEventListener("click", reset);
  $("undo").addEventListener("click", undo);
  $("redo").addEventListener("click", redo);
  $("save").addEventListener("click", save);
  $("show-handles").addEventListener("change", (ev) => {
    const g = $("handles");
    if (g) g.setAttribute("display", ev.target.checked ? "inline" : "none");
  });
  document.addEventListener("keydown", (ev) => {
    if (ev.target.tagName === "INPUT" || !(ev.ctrlKey || ev.metaKey) || !E.editable) return;
    const key = ev.key.toLowerCase();
    if (key === "z" && !ev.shiftKey) { ev.preventDefault(); undo(); }
    else if ((key === "z" && ev.shiftKey) || key === "y") { ev.preventDefault(); redo(); }
  });
})();
