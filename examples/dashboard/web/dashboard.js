// walkgen dashboard: draws the state that /api/events streams (a top view, live plots), shows
// the chest camera, and sends velocity commands (keys, buttons) to /api/command. Plain
// JavaScript, no library: the page works offline.
"use strict";

const dashboard = {
  state: null,        // the last state from the server
  path: [],           // the true CoM's walked path
  history: [],        // [time, zmp error, speed, command speed, compute ms]
  command: { vx: 0, vy: 0, wz: 0 },
  limits: null,
  view: { scale: 400, cx: 0, cy: 0, follow: true },  // px per m; centre in the world [m]
  footstepsDrawn: 0,  // for tests: footsteps drawn in the last frame
  framesDrawn: 0,
  errors: [],
};
window.dashboard = dashboard;

const STEP = { vx: 0.005, vy: 0.0015, wz: 0.015 };  // per key press, as the terminal teleop

// --- the server -------------------------------------------------------------------------------
function connect() {
  const events = new EventSource("/api/events");
  events.onmessage = (e) => {
    try {
      onState(JSON.parse(e.data));
    } catch (err) {
      dashboard.errors.push(String(err));
    }
  };
  events.onerror = () => setStatus("offline", "offline: reconnecting…");
}

function onState(s) {
  dashboard.state = s;
  if (!dashboard.limits && s.max_command) {
    dashboard.limits = { vx: s.max_command[0], vy: s.max_command[1], wz: s.max_command[2] };
    document.getElementById("lim-vx").textContent = "±" + dashboard.limits.vx.toFixed(4);
    document.getElementById("lim-vy").textContent = "±" + dashboard.limits.vy.toFixed(4);
    document.getElementById("lim-wz").textContent = "±" + dashboard.limits.wz.toFixed(4);
  }
  const last = dashboard.path[dashboard.path.length - 1];
  if (!last || Math.hypot(last[0] - s.com[0], last[1] - s.com[1]) > 0.005) dashboard.path.push(s.com);
  if (dashboard.path.length > 5000) dashboard.path.shift();
  const commandSpeed = Math.hypot(s.command[0], s.command[1]);
  dashboard.history.push([s.time, s.zmp_error * 100, s.speed, commandSpeed, s.compute_ms, s.mpc_ms]);
  if (dashboard.history.length > 300) dashboard.history.shift();
  const text = s.mode + (s.message ? ": " + s.message : "");
  setStatus(s.mode, text);
  document.getElementById("clock").textContent = "t = " + s.time.toFixed(1) + " s";
  showCommand(s.command);
  draw();
  drawPlots();
}

function setStatus(mode, text) {
  const el = document.getElementById("status");
  el.textContent = text;
  el.className = "status " + mode;
}

function showCommand(c) {
  document.getElementById("cmd-vx").textContent = c[0].toFixed(4);
  document.getElementById("cmd-vy").textContent = c[1].toFixed(4);
  document.getElementById("cmd-wz").textContent = c[2].toFixed(4);
}

async function sendCommand() {
  const error = document.getElementById("command-error");
  try {
    const res = await fetch("/api/command", {
      method: "POST",
      headers: { "Content-Type": "application/json" },
      body: JSON.stringify(dashboard.command),
    });
    const reply = await res.json();
    error.textContent = res.ok ? "" : reply.message;
  } catch (err) {
    error.textContent = "the server is not reachable";
  }
}

async function stop() {
  dashboard.command = { vx: 0, vy: 0, wz: 0 };
  try {
    await fetch("/api/stop", { method: "POST" });
  } catch (err) {
    document.getElementById("command-error").textContent = "the server is not reachable";
  }
}

function change(axis, sign) {
  if (!dashboard.limits) return;
  const limit = dashboard.limits[axis];
  const value = dashboard.command[axis] + sign * STEP[axis];
  dashboard.command[axis] = Math.max(-limit, Math.min(limit, Math.round(value * 1e6) / 1e6));
  sendCommand();
}

// --- keys and buttons ---------------------------------------------------------------------------
const KEYS = {
  KeyW: ["vx", 1], ArrowUp: ["vx", 1], KeyS: ["vx", -1], ArrowDown: ["vx", -1],
  KeyA: ["wz", 1], ArrowLeft: ["wz", 1], KeyD: ["wz", -1], ArrowRight: ["wz", -1],
  KeyQ: ["vy", 1], KeyE: ["vy", -1],
};
document.addEventListener("keydown", (e) => {
  if (e.code === "Space") {
    stop();
    e.preventDefault();
  } else if (KEYS[e.code]) {
    change(...KEYS[e.code]);
    e.preventDefault();
  }
});
const BUTTONS = {
  "btn-forward": ["vx", 1], "btn-backward": ["vx", -1], "btn-left": ["wz", 1],
  "btn-right": ["wz", -1], "btn-side-left": ["vy", 1], "btn-side-right": ["vy", -1],
};
for (const [id, args] of Object.entries(BUTTONS)) {
  document.getElementById(id).addEventListener("click", () => change(...args));
}
document.getElementById("btn-stop").addEventListener("click", stop);

// --- the top view ---------------------------------------------------------------------------------
const canvas = document.getElementById("topview");
const ctx = canvas.getContext("2d");

function toPx(p) {
  const v = dashboard.view;
  return [canvas.width / 2 + (p[0] - v.cx) * v.scale, canvas.height / 2 - (p[1] - v.cy) * v.scale];
}

function rect(p, yaw, length, width, fill, stroke, dashed) {
  const [x, y] = toPx(p);
  const s = dashboard.view.scale;
  ctx.save();
  ctx.translate(x, y);
  ctx.rotate(-yaw);
  ctx.setLineDash(dashed ? [4, 3] : []);
  if (fill) {
    ctx.fillStyle = fill;
    ctx.fillRect(-length * s / 2, -width * s / 2, length * s, width * s);
  }
  if (stroke) {
    ctx.strokeStyle = stroke;
    ctx.lineWidth = 2;
    ctx.strokeRect(-length * s / 2, -width * s / 2, length * s, width * s);
  }
  ctx.restore();
}

function dot(p, r, color) {
  const [x, y] = toPx(p);
  ctx.fillStyle = color;
  ctx.beginPath();
  ctx.arc(x, y, r, 0, 2 * Math.PI);
  ctx.fill();
}

function polyline(points, color, width) {
  if (points.length < 2) return;
  ctx.strokeStyle = color;
  ctx.lineWidth = width;
  ctx.setLineDash([]);
  ctx.beginPath();
  points.forEach((p, i) => {
    const [x, y] = toPx(p);
    if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
  });
  ctx.stroke();
}

function grid() {
  const v = dashboard.view;
  ctx.strokeStyle = "#e4e4e4";
  ctx.lineWidth = 1;
  const half = [canvas.width / 2 / v.scale, canvas.height / 2 / v.scale];
  for (let x = Math.floor(v.cx - half[0]); x <= v.cx + half[0]; x += 0.5) {
    const [px] = toPx([x, 0]);
    ctx.beginPath(); ctx.moveTo(px, 0); ctx.lineTo(px, canvas.height); ctx.stroke();
  }
  for (let y = Math.floor(v.cy - half[1]); y <= v.cy + half[1]; y += 0.5) {
    const [, py] = toPx([0, y]);
    ctx.beginPath(); ctx.moveTo(0, py); ctx.lineTo(canvas.width, py); ctx.stroke();
  }
  ctx.fillStyle = "#999";
  ctx.fillText("grid 0.5 m", 6, canvas.height - 6);
}

function draw() {
  const s = dashboard.state;
  if (!s) return;
  const v = dashboard.view;
  if (v.follow) { v.cx = s.com[0]; v.cy = s.com[1]; }
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  grid();
  for (const o of s.obstacles) {  // x, y, radius, margin
    const [x, y] = toPx(o);
    ctx.fillStyle = "#b0bec5";
    ctx.beginPath(); ctx.arc(x, y, o[2] * v.scale, 0, 2 * Math.PI); ctx.fill();
    ctx.strokeStyle = "#78909c"; ctx.setLineDash([3, 3]);
    ctx.beginPath(); ctx.arc(x, y, (o[2] + o[3]) * v.scale, 0, 2 * Math.PI); ctx.stroke();
  }
  for (const o of s.seen_obstacles || []) {  // found in the camera's depth: x, y, radius
    const [x, y] = toPx(o);
    ctx.strokeStyle = "#f57c00"; ctx.lineWidth = 2; ctx.setLineDash([6, 3]);
    ctx.beginPath(); ctx.arc(x, y, o[2] * v.scale, 0, 2 * Math.PI); ctx.stroke();
  }
  if (s.target) rect(s.target, 0, 0.12, 0.12, "#d32f2f");
  polyline(dashboard.path, "#81c784", 2);
  const [length, width] = s.foot_size;
  let drawn = 0;
  for (const f of s.footsteps) { rect([f[0], f[1]], f[2], length, width, null, "#1565c0", true); ++drawn; }
  dashboard.footstepsDrawn = drawn;
  rect([s.feet.swing[0], s.feet.swing[1]], s.feet.swing[2], length, width, "#90a4ae");
  rect([s.feet.support[0], s.feet.support[1]], s.feet.support[2], length, width, "#455a64");
  polyline(s.com_plan, "#2e7d32", 1);
  polyline(s.zmp_plan, "#ef6c00", 2);
  for (const z of s.zmp_measured) dot(z, 2, "#8e24aa");
  dot(s.zmp, 4, "#ef6c00");
  dot(s.com, 5, "#2e7d32");
  dashboard.framesDrawn += 1;
}

canvas.addEventListener("wheel", (e) => {
  dashboard.view.scale = Math.max(20, Math.min(2000, dashboard.view.scale * (e.deltaY < 0 ? 1.15 : 1 / 1.15)));
  draw();
  e.preventDefault();
}, { passive: false });
let dragging = null;
canvas.addEventListener("mousedown", (e) => { dragging = [e.clientX, e.clientY]; dashboard.view.follow = false; });
window.addEventListener("mouseup", () => { dragging = null; });
window.addEventListener("mousemove", (e) => {
  if (!dragging) return;
  const k = canvas.width / canvas.clientWidth / dashboard.view.scale;
  dashboard.view.cx -= (e.clientX - dragging[0]) * k;
  dashboard.view.cy += (e.clientY - dragging[1]) * k;
  dragging = [e.clientX, e.clientY];
  draw();
});
canvas.addEventListener("dblclick", () => { dashboard.view.follow = true; draw(); });

// --- live plots ---------------------------------------------------------------------------------
function plot(id, title, series, rows) {
  const c = document.getElementById(id);
  const g = c.getContext("2d");
  const h = rows || dashboard.history;
  g.clearRect(0, 0, c.width, c.height);
  g.fillStyle = "#333";
  g.font = "11px sans-serif";
  g.fillText(title, 4, 11);
  if (h.length < 2) return;
  let max = -Infinity, min = Infinity;
  for (const [column] of series) for (const row of h) { max = Math.max(max, row[column]); min = Math.min(min, row[column]); }
  min = Math.min(min, 0);
  if (max <= min) max = min + 1e-9;
  const x = (i) => 4 + (c.width - 8) * i / (h.length - 1);
  const y = (value) => c.height - 4 - (c.height - 20) * (value - min) / (max - min);
  let labelX = 4 + g.measureText(title).width + 14;  // the series' labels follow the title
  series.forEach(([column, color, label]) => {
    g.strokeStyle = color;
    g.lineWidth = 1.5;
    g.beginPath();
    h.forEach((row, i) => { if (i === 0) g.moveTo(x(i), y(row[column])); else g.lineTo(x(i), y(row[column])); });
    g.stroke();
    g.fillStyle = color;
    const text = label + " " + h[h.length - 1][column].toPrecision(4);
    g.fillText(text, labelX, 11);
    labelX += g.measureText(text).width + 12;
  });
  g.fillStyle = "#999";
  g.fillText("max " + max.toPrecision(3), c.width - 70, c.height - 6);
  if (min < 0) g.fillText("min " + min.toPrecision(3), c.width - 70, 24);
}

// --- the training view (walkgen_dashboard --training DIR) -----------------------------------------
// Plots the newest CSV log of the run: reward (mean_reward, else the first column with "reward"
// or "return"), success rate (wins / episodes) and losses (columns ending in _loss or _mse).
async function refreshTraining() {
  let reply;
  try {
    reply = await (await fetch("/api/training")).json();
    if (!reply.enabled) return false;  // not started with --training: no panel, no polling
  } catch (err) {
    return true;
  }
  document.getElementById("training-panel").hidden = false;
  document.getElementById("training-dir").textContent = "(" + reply.dir + ")";
  const file = reply.files.find((f) => f.rows && f.rows.length > 1);
  const message = document.getElementById("training-message");
  if (!file) {
    message.textContent = reply.message || "no CSV log with two rows yet in " + reply.dir;
    return true;
  }
  message.textContent = file.name + ": " + file.rows.length + " rows";
  const col = (name) => file.columns.indexOf(name);
  const find = (test) => file.columns.findIndex(test);
  const reward = col("mean_reward") >= 0 ? col("mean_reward") : find((c) => /reward|return/.test(c));
  const rows = file.rows.map((r) => r.slice());
  if (reward >= 0) plot("plot-reward", "reward (" + file.columns[reward] + ")", [[reward, "#2e7d32", "last"]], rows);
  const wins = col("wins"), episodes = col("episodes");
  if (wins >= 0 && episodes >= 0) {
    const k = file.columns.length;
    rows.forEach((r) => r.push(r[episodes] > 0 ? r[wins] / r[episodes] : 0));
    plot("plot-success", "success rate (wins / episodes)", [[k, "#1565c0", "last"]], rows);
  }
  const colors = ["#ef6c00", "#8e24aa", "#00838f", "#6d4c41"];
  const losses = file.columns.map((c, i) => [i, c]).filter(([, c]) => /(_loss|_mse)$/.test(c)).slice(0, 4);
  if (losses.length) plot("plot-losses", "losses", losses.map(([i, c], k) => [i, colors[k], c]), rows);
  dashboard.trainingRows = file.rows.length;
  return true;
}

(async () => {
  if (await refreshTraining()) setInterval(refreshTraining, 2000);
})();

function drawPlots() {
  plot("plot-zmp", "ZMP error [cm]", [[1, "#8e24aa", "mean"]]);
  plot("plot-speed", "speed [m/s]", [[2, "#2e7d32", "CoM"], [3, "#1565c0", "command"]]);
  plot("plot-compute", "compute time per tick [ms]", [[5, "#c62828", "NMPC (QP)"], [4, "#ef6c00", "all"]]);
}

// --- the camera -----------------------------------------------------------------------------------
function refreshCamera() {
  for (const which of ["rgb", "depth"]) {
    const img = document.getElementById("camera-" + which);
    const next = new Image();
    next.onload = () => {
      img.src = next.src;
      document.getElementById("camera-message").textContent = "";
    };
    next.onerror = async () => {
      try {
        const res = await fetch("/api/camera/" + which + ".jpg");
        if (!res.ok) document.getElementById("camera-message").textContent = (await res.json()).message;
      } catch (err) { /* offline: the status says so */ }
    };
    next.src = "/api/camera/" + which + ".jpg?t=" + Date.now();
  }
}

connect();
refreshCamera();
setInterval(refreshCamera, 1000);
