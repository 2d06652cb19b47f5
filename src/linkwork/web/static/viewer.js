// linkwork viewer: the mechanism, its plans and charts over a precomputed cycle.
//
// Drawing transform of the scheme: SVG user units are millimetres, x to the right and y down, so a
// point at (x, y) metres is drawn at (1000 x, -1000 y).  The plans are drawn in millimetres of the
// sheet: a plan vector u is drawn u / scale mm long (scale in units per mm, data-scale on the svg),
// with y flipped the same way.  Everything comes from one payload (GET api/cycle, POST api/solve, or
// the data embedded by linkwork view --export); moving the crank only indexes its arrays.
"use strict";

(function () {
  const NS = "http://www.w3.org/2000/svg";
  const state = {
    data: null, // the payload shown
    base: null, // the payload of the mechanism as loaded
    embedded: false,
    index: 0,
    playing: false,
    position: 0, // fractional sample while playing
    last: null,
    chosen: null, // keys of the charted series
    update: [], // functions (i) -> void run on every change of the crank angle
  };

  const $ = (id) => document.getElementById(id);

  function svg(tag, attrs, parent) {
    const e = document.createElementNS(NS, tag);
    for (const k in attrs || {}) e.setAttribute(k, attrs[k]);
    if (parent) parent.appendChild(e);
    return e;
  }

  function html(tag, text, parent, attrs) {
    const e = document.createElement(tag);
    if (text !== undefined && text !== null) e.textContent = text;
    for (const k in attrs || {}) e.setAttribute(k, attrs[k]);
    if (parent) parent.appendChild(e);
    return e;
  }

  const X = (p) => (1000 * p[0]).toFixed(3);
  const Y = (p) => (-1000 * p[1]).toFixed(3);
  function fmt(v, digits) {
    if (v === null || v === undefined || !isFinite(v)) return "-";
    const a = Math.abs(v);
    if (a !== 0 && (a >= 1e6 || a < 1e-3)) return Number(v).toExponential((digits || 4) - 1);
    return String(Number(Number(v).toPrecision(digits || 4)));
  }

  // ------------------------------------------------------------------ loading

  async function start() {
    bindControls();
    const node = $("linkwork-data");
    if (node && node.textContent.trim()) {
      state.embedded = true;
      show(JSON.parse(node.textContent), true);
      return;
    }
    try {
      const r = await fetch("api/cycle", { headers: { Accept: "application/json" } });
      const body = await r.json();
      if (!r.ok) throw new Error(body.error || r.statusText);
      show(body, true);
    } catch (err) {
      showError(String(err.message || err));
    }
  }

  function show(data, isBase) {
    state.data = data;
    if (isBase) state.base = data;
    $("loading").hidden = true;
    document.title = data.name + ": linkwork viewer";
    $("title").textContent = data.name;
    $("formula").textContent = data.structure.formula;
    state.update = [];
    const n = data.angles_deg.length;
    const slider = $("angle");
    slider.max = String(n - 1);
    state.index = Math.min(state.index, n - 1);
    buildScheme(data);
    buildPlan(data, "velocity");
    buildPlan(data, "acceleration");
    buildCharts(data);
    buildStructure(data);
    if (isBase) buildParams(data);
    setIndex(state.index);
  }

  // ------------------------------------------------------------------ the scheme

  // The drawing comes whole from the payload's scene (linkwork.scene, the one the figures and DXF draw):
  // items in the axes of their links, placed at the links' poses of the sample shown; labels where the
  // scene placed them.  Items of the frame (link 0) are drawn once.
  const GROUP = { path: "paths", hatch: "ground", support: "ground", guide: "ground" };
  const CLASS = { pivot: "joint" };

  function placeAt(pose, xy) {
    if (!pose || pose[0] === null) return null;
    const c = Math.cos(pose[2]), s = Math.sin(pose[2]);
    return xy.map((v) => [pose[0] + c * v[0] - s * v[1], pose[1] + s * v[0] + c * v[1]]);
  }

  function buildScheme(data) {
    const root = $("scheme");
    root.replaceChildren();
    const scene = data.scene;
    const [x0, y0, x1, y1] = scene.extent;
    const pad = 2000 * scene.r; // mm: two pivots' radii
    root.setAttribute("viewBox", [1000 * x0 - pad, -1000 * y1 - pad, 1000 * (x1 - x0) + 2 * pad, 1000 * (y1 - y0) + 2 * pad]
      .map((v) => v.toFixed(3)).join(" "));
    root.setAttribute("preserveAspectRatio", "xMidYMid meet");
    root.setAttribute("data-transform", "x_svg = 1000 x, y_svg = -1000 y (mm, x and y in m)");
    const groups = {};
    for (const id of ["paths", "ground", "links", "pairs", "labels"]) groups[id] = svg("g", { id: id }, root);
    groups.labels.setAttribute("font-size", (1000 * scene.em).toFixed(3));

    // trajectories of the moving points
    const pos = data.positions;
    for (const p of scene.paths) {
      let d = "", pen = false;
      for (let i = 0; i < pos.length; i++) {
        const xy = pos[i][p];
        if (!xy || xy[0] === null) { pen = false; continue; }
        d += (pen ? "L" : "M") + X(xy) + "," + Y(xy);
        pen = true;
      }
      if (d) svg("path", { class: "path", d: d, "data-point": data.points[p].label }, groups.paths);
    }
    for (const item of scene.items) drawItem(scene, item, groups[GROUP[item.kind] || (item.link === 0 || item.radius ? "pairs" : "links")]);
    for (const lab of scene.labels) {
      const t = svg("text", { class: lab.kind === "link" ? "link-number" : "label", "text-anchor": "middle", "dominant-baseline": "central" }, groups.labels);
      t.textContent = lab.text;
      state.update.push((i) => {
        const c = lab.centre[i];
        if (!c || c[0] === null) { t.setAttribute("visibility", "hidden"); return; }
        t.setAttribute("visibility", "visible");
        t.setAttribute("x", X(c)); t.setAttribute("y", Y(c));
      });
    }
    groups.paths.setAttribute("visibility", $("show-paths").checked ? "visible" : "hidden");
  }

  // one item: a circle (pivot, marker), an outline (polygon), a line or a polyline
  function drawItem(scene, item, g) {
    const cls = CLASS[item.kind] || item.kind;
    const attrs = { class: cls };
    if (item.kind === "bar" || item.kind === "plate") attrs["data-link"] = item.name;
    else if (item.radius) { attrs["data-point"] = item.name.split(".").pop(); attrs["data-joint"] = item.name; }
    else attrs["data-joint"] = item.name;
    const tag = item.radius ? "circle" : item.closed ? "polygon" : item.xy.length === 2 ? "line" : "polyline";
    const e = svg(tag, attrs, g);
    if (item.radius) e.setAttribute("r", (1000 * item.radius).toFixed(4));
    const put = (xy) => {
      if (!xy) { e.setAttribute("visibility", "hidden"); return; }
      e.setAttribute("visibility", "visible");
      if (item.radius) { e.setAttribute("cx", X(xy[0])); e.setAttribute("cy", Y(xy[0])); }
      else if (tag === "line") {
        e.setAttribute("x1", X(xy[0])); e.setAttribute("y1", Y(xy[0]));
        e.setAttribute("x2", X(xy[1])); e.setAttribute("y2", Y(xy[1]));
      } else e.setAttribute("points", xy.map((v) => X(v) + "," + Y(v)).join(" "));
    };
    if (item.link === 0) put(item.xy);
    else state.update.push((i) => put(placeAt(scene.poses[i][item.link], item.xy)));
  }

  // ------------------------------------------------------------------ the plans

  function buildPlan(data, kind) {
    const root = $(kind + "-plan");
    root.replaceChildren();
    const plan = data.plans[kind];
    const look = data.scene.plans[kind];
    const scale = plan.scale_per_mm;
    root.setAttribute("data-scale", String(scale));
    root.setAttribute("data-transform", "x_svg = u_x / scale, y_svg = -u_y / scale (mm of the drawing)");
    // one frame for the whole cycle, so that the plan does not jump while the crank turns (the scene's:
    // it holds the plans of 95 % of the positions; near a dead point accelerations grow without bound)
    const [x0, y0, x1, y1] = look.frame;
    const m = Math.max(x1 - x0, y1 - y0, 1e-9);
    const pad = 0.1 * m;
    root.setAttribute("viewBox", [x0 - pad, -y1 - pad, x1 - x0 + 2 * pad, y1 - y0 + 2 * pad].map((v) => v.toFixed(3)).join(" "));
    const defs = svg("defs", {}, root);
    for (const k of KINDS) {
      const mk = svg("marker", { id: `${kind}-head-${k}`, viewBox: "0 0 10 10", refX: "10", refY: "5", orient: "auto-start-reverse", markerUnits: "userSpaceOnUse" }, defs);
      mk.setAttribute("markerWidth", (0.03 * m).toFixed(3));
      mk.setAttribute("markerHeight", (0.03 * m).toFixed(3));
      svg("path", { d: "M0,0 L10,5 L0,10 z", class: "head " + k }, mk);
    }
    const grid = svg("g", {}, root);
    svg("line", { class: "grid", x1: x0 - pad, y1: 0, x2: x1 + pad, y2: 0 }, grid);
    svg("line", { class: "grid", x1: 0, y1: -y1 - pad, x2: 0, y2: -y0 + pad }, grid);
    const lines = svg("g", {}, root);
    const dots = svg("g", { "font-size": look.em.toFixed(3) }, root);
    const at = (i, j) => {
      const v = plan.values[i][j];
      return v && v[0] !== null ? [v[0] / scale, -v[1] / scale] : null;
    };
    const pole = plan.labels.indexOf("p");
    const drawn = [];
    for (const j of plan.absolute) drawn.push({ from: pole, to: j, kind: "absolute" });
    for (const v of plan.vectors) drawn.push(v);
    const els = drawn.map((v) => svg("line", {
      class: "vec " + v.kind, "data-kind": v.kind, "data-from": plan.labels[v.from], "data-to": plan.labels[v.to],
      "marker-end": `url(#${kind}-head-${KINDS.includes(v.kind) ? v.kind : "rotation"})`,
    }, lines));
    const marks = plan.labels.map((lab, j) => {
      const c = svg("circle", { class: "dot", r: (0.012 * m).toFixed(4), "data-label": lab }, dots);
      const main = j === pole || plan.absolute.includes(j); // a point of the mechanism, not of the construction
      const t = svg("text", { class: main ? "plabel" : "plabel minor", "text-anchor": "middle", "dominant-baseline": "central" }, dots);
      return [c, t];
    });
    legend(root, kind, look.kinds);
    const caption = $(kind + "-caption");
    const unit = plan.unit === "m/s" ? "(m/s)/mm" : "(m/s²)/mm";
    const mu = kind === "velocity" ? "μv" : "μa";
    state.update.push((i) => {
      drawn.forEach((v, k) => {
        const a = at(i, v.from), b = at(i, v.to), e = els[k];
        const zero = a && b && Math.hypot(b[0] - a[0], b[1] - a[1]) < 1e-9 * m;
        if (!a || !b || zero) { e.setAttribute("visibility", "hidden"); return; }
        e.setAttribute("visibility", "visible");
        e.setAttribute("x1", a[0].toFixed(4)); e.setAttribute("y1", a[1].toFixed(4));
        e.setAttribute("x2", b[0].toFixed(4)); e.setAttribute("y2", b[1].toFixed(4));
      });
      plan.labels.forEach((lab, j) => {
        const p = at(i, j), [c, t] = marks[j];
        const text = look.text[i][j], centre = look.centres[i][j];
        if (!p) { c.setAttribute("visibility", "hidden"); t.setAttribute("visibility", "hidden"); return; }
        c.setAttribute("visibility", "visible");
        c.setAttribute("cx", p[0].toFixed(4)); c.setAttribute("cy", p[1].toFixed(4));
        // points that coincide share one label, the scene's (e.g. "e, knife_upper.edge")
        if (!text || !centre || centre[0] === null) { t.setAttribute("visibility", "hidden"); return; }
        t.setAttribute("visibility", "visible");
        t.textContent = text;
        t.setAttribute("x", centre[0].toFixed(3)); t.setAttribute("y", (-centre[1]).toFixed(3));
      });
      const parts = plan.absolute.map((j) => {
        const v = plan.values[i][j];
        return v && v[0] !== null ? `${plan.labels[j]} ${fmt(Math.hypot(v[0], v[1]), 3)}` : `${plan.labels[j]} -`;
      });
      caption.textContent = `${kind} plan, pole p, ${mu} = ${scale} ${unit} of the plan drawn full size (shown scaled to fit); ` +
        `|${kind === "velocity" ? "v" : "a"}| in ${plan.unit}: ${parts.join(", ")}`;
    });
  }

  const KINDS = ["absolute", "rotation", "normal", "tangential", "transport", "coriolis", "sliding"];

  // the kinds of vector the plan draws over the cycle, each a short stroke in its style and its name
  function legend(root, kind, kinds) {
    const old = document.getElementById(kind + "-legend");
    if (old) old.remove();
    const box = html("div", null, null, { id: kind + "-legend", class: "legend" });
    root.parentNode.insertBefore(box, root.nextSibling);
    for (const k in kinds) {
      const item = html("span", null, box, { class: "legend-item" });
      const s = svg("svg", { width: "26", height: "8", viewBox: "0 0 26 8" }, item);
      svg("line", { class: "vec " + k, x1: 1, y1: 4, x2: 25, y2: 4 }, s);
      item.appendChild(document.createTextNode(" " + kinds[k]));
    }
  }

  // ------------------------------------------------------------------ charts

  function buildCharts(data) {
    const choice = $("series-choice");
    choice.replaceChildren();
    const keys = data.series.map((s) => s.key);
    if (!state.chosen || !state.chosen.some((k) => keys.includes(k))) {
      const want = ["torque", keys.find((k) => k.startsWith("slider:") && k.endsWith(":s")), "foundation:fy"];
      state.chosen = want.filter((k) => k && keys.includes(k));
      if (!state.chosen.length) state.chosen = keys.slice(0, 2);
    }
    for (const s of data.series) {
      const label = html("label", null, choice);
      const box = html("input", null, label, { type: "checkbox", "data-series": s.key });
      box.checked = state.chosen.includes(s.key);
      label.appendChild(document.createTextNode(` ${s.label}`));
      box.addEventListener("change", () => {
        state.chosen = Array.from(choice.querySelectorAll("input:checked")).map((b) => b.getAttribute("data-series"));
        drawCharts(state.data);
        setIndex(state.index);
      });
    }
    drawCharts(data);
  }

  function ticks(lo, hi, count) {
    const span = hi - lo || Math.abs(hi) || 1;
    const raw = span / count, mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 2.5, 5, 10].map((f) => f * mag).find((s) => s >= raw);
    const out = [];
    for (let v = Math.ceil(lo / step) * step; v <= hi + 1e-9 * span; v += step) out.push(Math.abs(v) < 1e-12 * span ? 0 : v);
    return out;
  }

  // a chart's viewBox (W x H) and the margins of its plot (left, right, top, bottom)
  const CHART = { W: 640, H: 150, L: 64, R: 12, T: 20, B: 22 };

  function drawCharts(data) {
    const root = $("charts");
    root.replaceChildren();
    state.chartUpdate = [];
    const { W, H, L, R, T, B } = CHART;
    const n = data.turn_deg.length;
    const xOf = (i) => L + (W - L - R) * (data.turn_deg[i] / 360);
    for (const key of state.chosen) {
      const s = data.series.find((x) => x.key === key);
      if (!s) continue;
      const g = svg("svg", { class: "chart", viewBox: `0 0 ${W} ${H}`, preserveAspectRatio: "none", "data-series": key }, root);
      const vals = s.values.filter((v) => v !== null);
      let lo = vals.length ? Math.min(...vals) : 0, hi = vals.length ? Math.max(...vals) : 1;
      if (hi - lo < 1e-12 * Math.max(1, Math.abs(hi))) { lo -= 1; hi += 1; }
      const yOf = (v) => T + (H - T - B) * (1 - (v - lo) / (hi - lo));
      g.setAttribute("data-lo", String(lo));
      g.setAttribute("data-hi", String(hi));
      g.setAttribute("data-transform", `x = ${L} + ${W - L - R} turn / 360, y = ${T} + ${H - T - B} (hi - v) / (hi - lo)`);
      svg("line", { class: "axis", x1: L, y1: H - B, x2: W - R, y2: H - B }, g);
      svg("line", { class: "axis", x1: L, y1: T, x2: L, y2: H - B }, g);
      if (lo < 0 && hi > 0) svg("line", { class: "zero", x1: L, y1: yOf(0), x2: W - R, y2: yOf(0) }, g);
      for (const t of ticks(lo, hi, 3)) {
        const y = yOf(t);
        svg("line", { class: "axis", x1: L - 4, y1: y, x2: L, y2: y }, g);
        svg("text", { x: L - 6, y: y + 4, "text-anchor": "end" }, g).textContent = fmt(t, 3);
      }
      for (const t of [0, 90, 180, 270, 360]) {
        const x = L + (W - L - R) * t / 360;
        svg("text", { x: x, y: H - 6, "text-anchor": "middle" }, g).textContent = t + "°";
      }
      let d = "", pen = false;
      for (let i = 0; i < n; i++) {
        const v = s.values[i];
        if (v === null) { pen = false; continue; }
        d += (pen ? "L" : "M") + xOf(i).toFixed(2) + "," + yOf(v).toFixed(2);
        pen = true;
      }
      svg("path", { class: "curve", d: d }, g);
      const title = svg("text", { class: "title", x: L + 4, y: 13 }, g);
      const cursor = svg("line", { class: "cursor", y1: T, y2: H - B }, g);
      g.addEventListener("pointerdown", (ev) => pick(ev, g));
      g.addEventListener("pointermove", (ev) => { if (ev.buttons) pick(ev, g); });
      state.chartUpdate.push((i) => {
        const x = xOf(i).toFixed(2);
        cursor.setAttribute("x1", x); cursor.setAttribute("x2", x);
        cursor.setAttribute("data-index", String(i));
        title.textContent = `${s.label}, ${s.unit}: ${fmt(s.values[i])} at ${data.turn_deg[i].toFixed(1)}° turned`;
      });
    }
    const note = html("div", "x: crank angle turned from the first position, deg; click a chart to move the crank there", root);
    note.className = "note";
  }

  // the crank angle under the pointer: the pointer mapped into the chart's own coordinates by the SVG's
  // current geometry (whatever its size, padding or border), then the plot's x axis turned back into degrees
  function pick(ev, g) {
    const ctm = g.getScreenCTM();
    if (!ctm) return;
    const pt = g.createSVGPoint();
    pt.x = ev.clientX; pt.y = ev.clientY;
    const x = pt.matrixTransform(ctm.inverse()).x;
    const turn = ((x - CHART.L) / (CHART.W - CHART.L - CHART.R)) * 360;
    const turns = state.data.turn_deg;
    let best = 0;
    for (let i = 1; i < turns.length; i++) if (Math.abs(turns[i] - turn) < Math.abs(turns[best] - turn)) best = i;
    setIndex(best);
  }

  // ------------------------------------------------------------------ structure

  function buildStructure(data) {
    const root = $("structure");
    root.replaceChildren();
    const s = data.structure;
    const tail = s.p4 ? ` - ${s.p4}` : "";
    html("p", `moving links n = ${s.n_links}, lower pairs p5 = ${s.p5}, higher pairs p4 = ${s.p4}; ` +
      `W = 3n - 2p5 - p4 = 3·${s.n_links} - 2·${s.p5}${tail} = ${s.dof}; redundant constraints q = ${s.redundant}`, root);
    const drive = data.drives[0];
    html("p", `drive: joint ${drive.joint}, ${fmt(drive.rpm, 4)} rpm ${drive.direction}`, root);
    table(root, ["#", "group", "kind", "links", "joints"],
      s.groups.map((g, i) => [i + 1, g.formula_part, g.kind, g.link_names.join(", "), g.joints.join(", ")]));
    html("p", `structural formula: ${s.formula}`, root);
    if (data.extremes.length) {
      table(root, ["", "stroke", "time ratio K", "+ stroke / other"], data.extremes.map((e) => [
        `${e.kind} ${e.name}`,
        e.kind === "slider" ? `${fmt(1000 * e.stroke)} mm` : `${fmt((e.stroke * 180) / Math.PI)}°`,
        fmt(e.time_ratio),
        fmt(e.forward_time_ratio),
      ]));
    }
    if (data.forces.available) {
      const c = data.forces.checks || {};
      html("p", `forces: power balance ${fmt(c.driving_torque_vs_power_balance, 2)}, momentum ${fmt(c.foundation_force_vs_momentum, 2)} (relative discrepancy of the cross-checks)`, root);
    } else {
      html("p", `forces: not computed (${data.forces.reason})`, root);
    }
    for (const e of data.events) html("p", `${e.kind}: ${e.message}`, root, { class: "warn" });
    for (const w of data.warnings.concat(s.warnings || [])) html("p", w, root, { class: "warn" });
  }

  function table(parent, head, rows) {
    const t = html("table", null, parent);
    const tr = html("tr", null, html("thead", null, t));
    for (const h of head) html("th", h, tr);
    const body = html("tbody", null, t);
    for (const row of rows) {
      const r = html("tr", null, body);
      for (const c of row) html("td", String(c), r);
    }
  }

  // ------------------------------------------------------------------ edits

  const DISPLAY = {
    length: ["mm", 1000], angle: ["deg", 180 / Math.PI], mass: ["kg", 1], inertia: ["kg m²", 1],
  };

  function buildParams(data) {
    const root = $("params");
    root.replaceChildren();
    const note = $("edit-note");
    const editable = data.editable && !state.embedded;
    if (state.embedded) note.textContent = "This page was exported with its cycle precomputed; to edit the mechanism, run linkwork view on its file.";
    else if (!data.editable) note.textContent = "This mechanism was given without its description: it cannot be edited here.";
    else note.textContent = "Values as in the file (lengths in mm, angles in degrees); Apply solves the mechanism again on the server.";
    $("apply").disabled = !editable;
    $("reset").disabled = !editable;
    let group = null;
    for (const p of data.parameters || []) {
      if (p.group !== group) {
        group = p.group;
        html("h3", group, root);
      }
      const [unit, k] = DISPLAY[p.kind];
      const row = html("label", null, root, { class: "param" });
      html("span", p.name + (p.note ? ` (${p.note})` : ""), row, { class: "name", title: p.name });
      const input = html("input", null, row, { type: "number", step: "any", "data-param": p.name, "data-kind": p.kind });
      input.value = String(Number((p.value * k).toPrecision(10)));
      input.defaultValue = input.value;
      input.disabled = !editable;
      input.addEventListener("input", () => row.classList.toggle("changed", input.value !== input.defaultValue));
      html("span", unit, row);
    }
  }

  function overrides() {
    const out = {};
    const bad = [];
    for (const input of $("params").querySelectorAll("input[data-param]")) {
      if (input.value === input.defaultValue) continue;
      const v = Number(input.value);
      if (input.value.trim() === "" || !isFinite(v)) { bad.push(input.getAttribute("data-param")); continue; }
      out[input.getAttribute("data-param")] = v / DISPLAY[input.getAttribute("data-kind")][1];
    }
    return { out, bad };
  }

  async function apply(ev) {
    ev.preventDefault();
    const { out, bad } = overrides();
    if (bad.length) { showError(bad.map((b) => `${b}: enter a number`).join("\n")); return; }
    $("apply").disabled = true;
    $("edit-status").textContent = "solving…";
    try {
      const r = await fetch("api/solve", {
        method: "POST", headers: { "Content-Type": "application/json", Accept: "application/json" },
        body: JSON.stringify({ overrides: out }),
      });
      const body = await r.json().catch(() => ({ error: `the server answered ${r.status}` }));
      if (!r.ok) { showError(body.error || `the server answered ${r.status}`); return; }
      hideError();
      show(body, false);
      $("edit-status").textContent = Object.keys(out).length ? `${Object.keys(out).length} value(s) changed` : "";
    } catch (err) {
      showError(`no answer from the server: ${err.message || err}`);
    } finally {
      $("apply").disabled = false;
      if ($("edit-status").textContent === "solving…") $("edit-status").textContent = "";
    }
  }

  function reset() {
    for (const input of $("params").querySelectorAll("input[data-param]")) {
      input.value = input.defaultValue;
      input.parentElement.classList.remove("changed");
    }
    hideError();
    $("edit-status").textContent = "";
    if (state.base) show(state.base, false);
  }

  function showError(text) {
    $("error-text").textContent = text;
    $("error").hidden = false;
    $("edit-status").textContent = "";
  }

  function hideError() {
    $("error").hidden = true;
    $("error-text").textContent = "";
  }

  // ------------------------------------------------------------------ the crank

  function setIndex(i) {
    const data = state.data;
    if (!data) return;
    const n = data.angles_deg.length;
    i = ((Math.round(i) % n) + n) % n;
    state.index = i;
    const slider = $("angle");
    if (Number(slider.value) !== i) slider.value = String(i);
    for (const f of state.update) f(i);
    for (const f of state.chartUpdate || []) f(i);
    const deg = data.angles_deg[i];
    const root = $("scheme");
    root.setAttribute("data-index", String(i));
    root.setAttribute("data-angle-deg", String(deg));
    $("angle-text").textContent = `crank ${(((deg % 360) + 360) % 360).toFixed(1)}°, turned ${data.turn_deg[i].toFixed(1)}° (sample ${i + 1} of ${n})`;
    const note = $("pose-note");
    note.hidden = data.valid[i];
    note.textContent = data.valid[i] ? "" : "The mechanism does not assemble at this crank angle.";
  }

  function frame(t) {
    if (!state.playing) { state.last = null; return; }
    if (state.last !== null) {
      const n = state.data.angles_deg.length;
      const period = state.data.period_s || 4;
      state.position = (state.position + ((t - state.last) / 1000) * Number($("speed").value) * n / period) % n;
      const i = Math.floor(state.position);
      if (i !== state.index) setIndex(i);
    }
    state.last = t;
    requestAnimationFrame(frame);
  }

  function play(on) {
    state.playing = on;
    $("play").textContent = on ? "Pause" : "Play";
    $("play").setAttribute("aria-pressed", String(on));
    if (on) { state.position = state.index; state.last = null; requestAnimationFrame(frame); }
  }

  function bindControls() {
    $("angle").addEventListener("input", (ev) => {
      setIndex(Number(ev.target.value));
      state.position = state.index;
    });
    $("play").addEventListener("click", () => play(!state.playing));
    $("show-paths").addEventListener("change", (ev) => {
      const g = $("paths");
      if (g) g.setAttribute("visibility", ev.target.checked ? "visible" : "hidden");
    });
    $("edit-form").addEventListener("submit", apply);
    $("reset").addEventListener("click", reset);
    $("error-close").addEventListener("click", hideError);
    document.addEventListener("keydown", (ev) => {
      if (ev.target.tagName === "INPUT" || ev.target.tagName === "SELECT") return;
      if (ev.key === " ") { ev.preventDefault(); play(!state.playing); }
    });
  }

  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
