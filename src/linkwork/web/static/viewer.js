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

  function bounds(data) {
    let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
    for (const pose of data.positions) {
      for (let p = 0; p < pose.length; p++) {
        const xy = pose[p];
        if (!xy || xy[0] === null || data.points[p].virtual) continue;
        x0 = Math.min(x0, xy[0]); x1 = Math.max(x1, xy[0]);
        y0 = Math.min(y0, xy[1]); y1 = Math.max(y1, xy[1]);
      }
    }
    if (!isFinite(x0)) { x0 = -1; x1 = 1; y0 = -1; y1 = 1; }
    return { x0, x1, y0, y1, size: Math.max(x1 - x0, y1 - y0, 1e-6) };
  }

  function firstValid(data) {
    const i = data.valid.indexOf(true);
    return i < 0 ? 0 : i;
  }

  function buildScheme(data) {
    const root = $("scheme");
    root.replaceChildren();
    const b = bounds(data);
    const size = 1000 * b.size; // mm
    const r = 0.012 * size;
    const pad = 0.12 * size;
    const vb = [1000 * b.x0 - pad, -1000 * b.y1 - pad, 1000 * (b.x1 - b.x0) + 2 * pad, 1000 * (b.y1 - b.y0) + 2 * pad];
    root.setAttribute("viewBox", vb.map((v) => v.toFixed(3)).join(" "));
    root.setAttribute("preserveAspectRatio", "xMidYMid meet");
    root.setAttribute("data-transform", "x_svg = 1000 x, y_svg = -1000 y (mm, x and y in m)");
    const defs = svg("defs", {}, root);
    const h = 0.7 * r;
    const pat = svg("pattern", { id: "hatch", patternUnits: "userSpaceOnUse", width: h, height: h }, defs);
    svg("path", { d: `M0,${h} L${h},0`, stroke: "#000", "stroke-width": (0.12 * h).toFixed(4) }, pat);
    const fontSize = (0.032 * size).toFixed(3);
    const gPaths = svg("g", { id: "paths" }, root);
    const gGround = svg("g", { id: "ground" }, root);
    const gLinks = svg("g", { id: "links" }, root);
    const gPairs = svg("g", { id: "pairs" }, root);
    const gLabels = svg("g", { id: "labels", "font-size": fontSize }, root);
    const pos = data.positions;
    const first = firstValid(data);

    // trajectories of the moving points
    const drawn = new Set();
    for (const link of data.links) {
      if (link.index === 0 || link.virtual) continue;
      for (const p of link.draw) drawn.add(p);
    }
    for (const p of drawn) {
      let d = "", pen = false;
      for (let i = 0; i < pos.length; i++) {
        const xy = pos[i][p];
        if (!xy || xy[0] === null) { pen = false; continue; }
        d += (pen ? "L" : "M") + X(xy) + "," + Y(xy);
        pen = true;
      }
      if (d) svg("path", { class: "path", d: d, "data-point": data.points[p].label }, gPaths);
    }

    // links: a bar through two points, a plate through more
    for (const link of data.links) {
      if (link.index === 0 || link.virtual || link.draw.length < 2) continue;
      let order = link.draw.slice();
      if (order.length > 2) {
        const xy = order.map((p) => pos[first][p]);
        if (xy.every((v) => v && v[0] !== null)) {
          const cx = xy.reduce((s, v) => s + v[0], 0) / xy.length;
          const cy = xy.reduce((s, v) => s + v[1], 0) / xy.length;
          const ang = xy.map((v) => Math.atan2(v[1] - cy, v[0] - cx));
          order = order.map((p, j) => [ang[j], p]).sort((u, v) => u[0] - v[0]).map((u) => u[1]);
        }
      }
      const shape = order.length === 2
        ? svg("line", { class: "bar", "data-link": link.name }, gLinks)
        : svg("polygon", { class: "plate", "data-link": link.name }, gLinks);
      const num = svg("text", { class: "link-number", "font-size": fontSize }, gLinks);
      num.textContent = String(link.index);
      state.update.push((i) => {
        const xy = order.map((p) => pos[i][p]);
        if (xy.some((v) => !v || v[0] === null)) { shape.setAttribute("visibility", "hidden"); num.setAttribute("visibility", "hidden"); return; }
        shape.setAttribute("visibility", "visible"); num.setAttribute("visibility", "visible");
        if (order.length === 2) {
          shape.setAttribute("x1", X(xy[0])); shape.setAttribute("y1", Y(xy[0]));
          shape.setAttribute("x2", X(xy[1])); shape.setAttribute("y2", Y(xy[1]));
        } else {
          shape.setAttribute("points", xy.map((v) => X(v) + "," + Y(v)).join(" "));
        }
        const mx = xy.reduce((s, v) => s + v[0], 0) / xy.length, my = xy.reduce((s, v) => s + v[1], 0) / xy.length;
        num.setAttribute("x", (1000 * mx + 0.8 * r).toFixed(3));
        num.setAttribute("y", (-1000 * my + 2.2 * r).toFixed(3));
      });
    }

    // pairs: pivots, supports, sliders on their guides
    const seen = new Set();
    data.pairs.forEach((pair, k) => {
      const [a] = pair.links;
      const pb = pair.points[1];
      if (pair.type === "revolute") {
        if (pair.frame_point !== null && pair.frame_point !== undefined) {
          const fixed = pos[first][pair.frame_point];
          if (fixed && fixed[0] !== null) support(gGround, fixed, r, pair.joint);
        }
        const key = pair.joint + "@" + data.points[pb].label;
        if (seen.has(key)) return;
        seen.add(key);
        const c = svg("circle", { class: "joint", r: r.toFixed(4), "data-point": data.points[pb].label, "data-joint": pair.joint }, gPairs);
        state.update.push((i) => place(c, pos[i][pb]));
      } else {
        const block = svg("polygon", { class: "block", "data-joint": pair.joint, "data-point": data.points[pb].label }, gPairs);
        if (a === 0) guide(gGround, data, pair, r);
        state.update.push((i) => {
          const p = pos[i][pb], u = pair.axis[i];
          if (!p || p[0] === null || !u || u[0] === null) { block.setAttribute("visibility", "hidden"); return; }
          block.setAttribute("visibility", "visible");
          const w = [-u[1], u[0]];
          const s = r / 1000;
          const corner = (cu, cw) => [p[0] + s * (cu * u[0] + cw * w[0]), p[1] + s * (cu * u[1] + cw * w[1])];
          const pts = [corner(-2, -1), corner(2, -1), corner(2, 1), corner(-2, 1)];
          block.setAttribute("points", pts.map((v) => X(v) + "," + Y(v)).join(" "));
        });
      }
    });

    // markers (points no pair uses) and labels
    data.points.forEach((pt, p) => {
      if (pt.virtual) return;
      if (pt.link === 0) {
        const xy = pos[first][p];
        if (!xy || xy[0] === null) return;
        const t = svg("text", { class: "label", x: (1000 * xy[0] + 1.3 * r).toFixed(3), y: (-1000 * xy[1] - 1.3 * r).toFixed(3) }, gLabels);
        t.textContent = pt.label;
        return;
      }
      if (!pt.joint) {
        const m = svg("circle", { class: "marker", r: (0.45 * r).toFixed(4), "data-point": pt.label }, gPairs);
        state.update.push((i) => place(m, pos[i][p]));
      }
    });
    const labelled = new Set();
    data.points.forEach((pt, p) => {
      if (pt.virtual || pt.link === 0 || labelled.has(pt.label)) return;
      labelled.add(pt.label);
      const t = svg("text", { class: "label" }, gLabels);
      t.textContent = pt.label.includes(".") ? pt.label.split(".").pop() : pt.label;
      state.update.push((i) => {
        const xy = pos[i][p];
        if (!xy || xy[0] === null) { t.setAttribute("visibility", "hidden"); return; }
        t.setAttribute("visibility", "visible");
        t.setAttribute("x", (1000 * xy[0] + 1.3 * r).toFixed(3));
        t.setAttribute("y", (-1000 * xy[1] - 1.3 * r).toFixed(3));
      });
    });
    gPaths.setAttribute("visibility", $("show-paths").checked ? "visible" : "hidden");
  }

  function place(circle, xy) {
    if (!xy || xy[0] === null) { circle.setAttribute("visibility", "hidden"); return; }
    circle.setAttribute("visibility", "visible");
    circle.setAttribute("cx", X(xy));
    circle.setAttribute("cy", Y(xy));
  }

  // a hinge on the frame: a triangle below the pivot standing on a hatched base
  function support(g, p, r, joint) {
    const cx = 1000 * p[0], cy = -1000 * p[1];
    const tri = [[cx, cy], [cx - 1.6 * r, cy + 2.8 * r], [cx + 1.6 * r, cy + 2.8 * r]];
    svg("polygon", { class: "support", "data-joint": joint, points: tri.map((v) => v[0].toFixed(3) + "," + v[1].toFixed(3)).join(" ") }, g);
    svg("line", { class: "support", x1: (cx - 2.6 * r).toFixed(3), y1: (cy + 2.8 * r).toFixed(3), x2: (cx + 2.6 * r).toFixed(3), y2: (cy + 2.8 * r).toFixed(3) }, g);
    svg("rect", { class: "ground", fill: "url(#hatch)", x: (cx - 2.6 * r).toFixed(3), y: (cy + 2.8 * r).toFixed(3), width: (5.2 * r).toFixed(3), height: (0.9 * r).toFixed(3) }, g);
  }

  // a guide on the frame: a line along the stroke of its slider, hatched on one side
  function guide(g, data, pair, r) {
    const pb = pair.points[1];
    let u = null, lo = Infinity, hi = -Infinity, o = null;
    for (let i = 0; i < data.positions.length; i++) {
      const p = data.positions[i][pb], a = pair.axis[i];
      if (!p || p[0] === null || !a || a[0] === null) continue;
      if (!u) { u = a; o = p; }
      const s = (p[0] - o[0]) * u[0] + (p[1] - o[1]) * u[1];
      lo = Math.min(lo, s); hi = Math.max(hi, s);
    }
    if (!u) return;
    const w = [-u[1], u[0]];
    const s0 = 1000 * lo - 3 * r, s1 = 1000 * hi + 3 * r, off = -1.3 * r;
    const at = (s, d) => [1000 * o[0] + s * u[0] + d * w[0], -(1000 * o[1] + s * u[1] + d * w[1])];
    const a0 = at(s0, off), a1 = at(s1, off);
    svg("line", { class: "guide", x1: a0[0].toFixed(3), y1: a0[1].toFixed(3), x2: a1[0].toFixed(3), y2: a1[1].toFixed(3) }, g);
    const step = 0.8 * r;
    let d = "";
    for (let s = s0; s <= s1 + 1e-9; s += step) {
      const p = at(s, off), q = at(s - 0.6 * r, off - 0.8 * r);
      d += `M${p[0].toFixed(3)},${p[1].toFixed(3)}L${q[0].toFixed(3)},${q[1].toFixed(3)}`;
    }
    svg("path", { class: "guide", d: d }, g);
  }

  // ------------------------------------------------------------------ the plans

  function buildPlan(data, kind) {
    const root = $(kind + "-plan");
    root.replaceChildren();
    const plan = data.plans[kind];
    const scale = plan.scale_per_mm;
    root.setAttribute("data-scale", String(scale));
    root.setAttribute("data-transform", "x_svg = u_x / scale, y_svg = -u_y / scale (mm of the drawing)");
    // one frame for the whole cycle, so that the plan does not jump while the crank turns: it holds the
    // plans of 95 % of the positions (near a dead point accelerations grow without bound)
    const lo = [[], []], hi = [[], []];
    for (const row of plan.values) {
      let a = [0, 0], b = [0, 0];
      for (const v of row) {
        if (!v || v[0] === null) continue;
        const p = [v[0] / scale, -v[1] / scale];
        a = [Math.min(a[0], p[0]), Math.min(a[1], p[1])];
        b = [Math.max(b[0], p[0]), Math.max(b[1], p[1])];
      }
      for (const k of [0, 1]) { lo[k].push(a[k]); hi[k].push(b[k]); }
    }
    const quantile = (xs, q) => {
      const s = xs.slice().sort((u, v) => u - v);
      return s.length ? s[Math.min(s.length - 1, Math.max(0, Math.round(q * (s.length - 1))))] : 0;
    };
    const x0 = quantile(lo[0], 0.025), y0 = quantile(lo[1], 0.025);
    const x1 = quantile(hi[0], 0.975), y1 = quantile(hi[1], 0.975);
    const m = Math.max(x1 - x0, y1 - y0, 1e-9);
    const pad = 0.1 * m;
    root.setAttribute("viewBox", [x0 - pad, y0 - pad, x1 - x0 + 2 * pad, y1 - y0 + 2 * pad].map((v) => v.toFixed(3)).join(" "));
    const defs = svg("defs", {}, root);
    const colours = { absolute: "#000", rotation: "#1f77b4", tangential: "#1f77b4", normal: "#2ca02c", transport: "#9467bd", coriolis: "#d62728", sliding: "#ff7f0e" };
    for (const k in colours) {
      const mk = svg("marker", { id: `${kind}-head-${k}`, viewBox: "0 0 10 10", refX: "10", refY: "5", markerWidth: "7", markerHeight: "7", orient: "auto-start-reverse", markerUnits: "userSpaceOnUse" }, defs);
      mk.setAttribute("markerWidth", (0.03 * m).toFixed(3));
      mk.setAttribute("markerHeight", (0.03 * m).toFixed(3));
      svg("path", { d: "M0,0 L10,5 L0,10 z", fill: colours[k] }, mk);
    }
    const grid = svg("g", {}, root);
    svg("line", { class: "grid", x1: x0 - pad, y1: 0, x2: x1 + pad, y2: 0 }, grid);
    svg("line", { class: "grid", x1: 0, y1: y0 - pad, x2: 0, y2: y1 + pad }, grid);
    const lines = svg("g", {}, root);
    const dots = svg("g", { "font-size": (0.045 * m).toFixed(3) }, root);
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
      "marker-end": `url(#${kind}-head-${v.kind in colours ? v.kind : "rotation"})`,
    }, lines));
    const marks = plan.labels.map((lab) => {
      const c = svg("circle", { class: "dot", r: (0.012 * m).toFixed(4), "data-label": lab }, dots);
      const t = svg("text", { class: /^(n_|k'+_)/.test(lab) ? "plabel minor" : "plabel" }, dots);
      t.textContent = lab;
      return [c, t];
    });
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
      const placed = [];
      plan.labels.forEach((lab, j) => {
        const p = at(i, j), [c, t] = marks[j];
        if (!p) { c.setAttribute("visibility", "hidden"); t.setAttribute("visibility", "hidden"); return; }
        c.setAttribute("visibility", "visible"); t.setAttribute("visibility", "visible");
        c.setAttribute("cx", p[0].toFixed(4)); c.setAttribute("cy", p[1].toFixed(4));
        // labels of coinciding plan points are stacked instead of overwritten
        const same = placed.filter((q) => Math.hypot(q[0] - p[0], q[1] - p[1]) < 0.03 * m).length;
        placed.push(p);
        t.setAttribute("x", (p[0] + 0.025 * m).toFixed(4));
        t.setAttribute("y", (p[1] - 0.025 * m + same * 0.08 * m).toFixed(4));
      });
      const parts = plan.absolute.map((j) => {
        const v = plan.values[i][j];
        return v && v[0] !== null ? `${plan.labels[j]} ${fmt(Math.hypot(v[0], v[1]), 3)}` : `${plan.labels[j]} -`;
      });
      caption.textContent = `${kind} plan, pole p, ${mu} = ${scale} ${unit} of the plan drawn full size (shown scaled to fit); ` +
        `|${kind === "velocity" ? "v" : "a"}| in ${plan.unit}: ${parts.join(", ")}`;
    });
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
