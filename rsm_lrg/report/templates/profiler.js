/* rsm-lrg interactive report: the prediction profiler, overlay plot and live surfaces.
 * Reads the fitted models from <script type="application/json" id="rsm-data"> and computes
 * what FitResult.predict(points, interval="both") computes (rsm_lrg/report/interactive.py).
 * User text only ever reaches the page through textContent or escaped for Plotly labels. */
(function () {
  "use strict";
  /* every object of the page data is prototype-free (see dict below): a name such as
   * __proto__, constructor or toString is an own key like any other */
  var DATA = JSON.parse(document.getElementById("rsm-data").textContent, function (k, v) {
    return v !== null && typeof v === "object" && !Array.isArray(v) ? Object.assign(Object.create(null), v) : v;
  });
  var MODELS = DATA.models;
  var CONTROLS = DATA.controls;
  /* the free numeric factors (a mixture's components are not free: they move together, see rebalance) */
  var NUMERIC = CONTROLS.filter(function (c) { return c.kind === "numeric" && !c.component; });
  var MIX = DATA.mixture || null;
  /* report --constraint/--bound: inequalities lhs <= rhs in actual units, as expression trees
     (rsm_lrg/report/region.py); a setting outside them is never "inside every limit" */
  var REGION = DATA.region || null;
  var FUNCS = {sqrt: Math.sqrt, exp: Math.exp, log: Math.log, log10: Math.log10, abs: Math.abs};
  function evalTree(t, s) {
    if (typeof t === "number") return t;
    if (t.f !== undefined) return s[t.f];
    if (t.call !== undefined) {
      var xs = t.args.map(function (a) { return evalTree(a, s); });
      if (t.call === "min") return Math.min.apply(null, xs);
      if (t.call === "max") return Math.max.apply(null, xs);
      return FUNCS[t.call](xs[0]);
    }
    var a = evalTree(t.a, s);
    if (t.op === "neg") return -a;
    var b = evalTree(t.b, s);
    return t.op === "+" ? a + b : t.op === "-" ? a - b : t.op === "*" ? a * b : t.op === "/" ? a / b : Math.pow(a, b);
  }
  function inStudyRegion(s) {
    if (!REGION) return true;
    for (var i = 0; i < REGION.constraints.length; i++) {
      var c = REGION.constraints[i], lo = evalTree(c.lhs, s), hi = evalTree(c.rhs, s);
      if (!(hi - lo >= -1e-9 * Math.max(1, Math.abs(lo), Math.abs(hi)))) return false;
    }
    return true;
  }

  function esc(s) {  /* Plotly reads <b>, <a href>, ... in labels: make user text plain */
    return String(s).replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;");
  }
  /* The page's one number format: rsm_lrg.present.format_number, digit for digit. `sig`
   * significant figures of the exact value, ties to even (as Python rounds); plain decimals
   * when the rounded value is in [1e-4, 1e5), otherwise 6.972 × 10⁻⁵ ("ascii": 6.972e-05);
   * trailing zeros dropped unless trim === false; "—" for a missing or non-finite value. */
  var SUP = {"-": "\u207b", "0": "\u2070", "1": "\u00b9", "2": "\u00b2", "3": "\u00b3", "4": "\u2074",
             "5": "\u2075", "6": "\u2076", "7": "\u2077", "8": "\u2078", "9": "\u2079"};
  function roundSig(a, sig) {  /* a > 0: [sig digits, decimal exponent] of a rounded to sig figures */
    var ex = a.toExponential(100).split("e");  /* 101 digits: every double's tie is exact within them */
    var d = ex[0].replace(".", ""), e = parseInt(ex[1], 10);
    var head = d.slice(0, sig), next = d.charAt(sig), rest = d.slice(sig + 1);
    var up = next > "5" || (next === "5" && (/[1-9]/.test(rest) || parseInt(head.charAt(sig - 1), 10) % 2 === 1));
    if (up) {
      var ds = head.split(""), i = ds.length - 1;
      while (i >= 0 && ds[i] === "9") { ds[i] = "0"; i--; }
      if (i >= 0) ds[i] = String(parseInt(ds[i], 10) + 1);
      else { ds.unshift("1"); ds.pop(); e += 1; }
      head = ds.join("");
    }
    return [head, e];
  }
  function trimZeros(s) { return s.indexOf(".") < 0 ? s : s.replace(/0+$/, "").replace(/\.$/, ""); }
  function fmt(x, sig, style, trim) {
    sig = Math.max(sig || 4, 1);
    if (x === null || x === undefined || typeof x !== "number" || !isFinite(x)) return "\u2014";
    if (x === 0) return trim === false ? (0).toFixed(sig - 1) : "0";
    var r = roundSig(Math.abs(x), sig), h = r[0], e = r[1], sign = x < 0 ? "-" : "", s;
    if (e >= -4 && e <= 4) {
      if (e >= 0) {
        var whole = h.length > e + 1 ? h.slice(0, e + 1) : h + "0".repeat(e + 1 - h.length);
        var frac = h.slice(e + 1);
        s = frac ? whole + "." + frac : whole;
      } else s = "0." + "0".repeat(-e - 1) + h;
      return sign + (trim === false ? s : trimZeros(s));
    }
    var mant = h.length > 1 ? h.charAt(0) + "." + h.slice(1) : h;
    if (trim !== false) mant = trimZeros(mant);
    if (style === "ascii") return sign + mant + "e" + (e < 0 ? "-" : "+") + (Math.abs(e) < 10 ? "0" : "") + Math.abs(e);
    return sign + mant + " \u00d7 " + power10(e);
  }
  /* Contour labels in the page's number format. Plotly writes a contour label with a d3 format;
   * ".4~r" (4 significant figures, plain decimals, trailing zeros dropped) is fmt's plain form,
   * so a response of size (largest |value| on the grid) outside [1e-2, 1e5) is drawn in units of
   * 10^E (E a multiple of 3, named on the colour bar) to keep every level in that form. Plotly
   * writes a negative label with the typographic minus (U+2212). */
  var LABEL_FORMAT = ".4~r";
  function plainNumber(v) { var a = Math.abs(v); return v === 0 || (a >= 1e-4 && a < 1e5); }
  function labelScale(z) {
    var a = 0;
    z.forEach(function (r) { r.forEach(function (v) { if (isFinite(v)) a = Math.max(a, Math.abs(v)); }); });
    return !(a > 0) || (a >= 1e-2 && a < 1e5) ? 0 : 3 * Math.floor(Math.log10(a) / 3);
  }
  function power10(e) { return "10" + String(e).split("").map(function (ch) { return SUP[ch]; }).join(""); }
  /* names (factors, levels, responses) are data, never object keys with a prototype: every
   * object indexed by a name is prototype-free, so __proto__, constructor or toString are
   * ordinary names */
  function dict() { return Object.create(null); }
  function copy() { var o = dict(); for (var i = 0; i < arguments.length; i++) Object.assign(o, arguments[i]); return o; }
  var AX = {exponentformat: "power", automargin: true};
  function axis(title) { return Object.assign({title: {text: title}}, AX); }

  // -- the model --------------------------------------------------------------------------
  function encode(f, x, decimals) {
    if (f.kind === "categoric") {
      var i = f.levels.indexOf(String(x));
      if (i < 0) throw new Error("not a level");
      return i;
    }
    var c = ((x - f.low) - (f.high - x)) / (f.high - f.low);
    if (decimals === null) return c;  /* a Gaussian process codes without rounding */
    var s = Math.pow(10, decimals);
    var r = Math.round(c * s);
    if (Math.abs(c * s - Math.trunc(c * s)) === 0.5) r = 2 * Math.round(c * s / 2);  /* numpy: half to even */
    return r / s + 0.0;
  }
  function modelRow(m, xc) {
    var row = [];
    for (var j = 0; j < m.terms.length; j++) {
      var t = m.terms[j];
      var parts = [];
      for (var i = 0; i < t.p.length; i++) {
        if (t.p[i] === 1) parts.push(xc[i]);
        else if (t.p[i] > 1) parts.push(Math.pow(xc[i], t.p[i]));
      }
      var v = 1.0;
      if (parts.length) { v = parts[0]; for (var q = 1; q < parts.length; q++) v = v * parts[q]; }
      if (t.diff && t.diff.length) v = v * (xc[t.diff[0]] - xc[t.diff[1]]);  /* full cubic AB(A-B) */
      if (!t.cat.length) { row.push(v); continue; }
      for (var k = 0; k < t.combos.length; k++) {
        var col = v;
        for (var h = 0; h < t.cat.length; h++) {
          var idx = xc[t.cat[h][0]], L = t.cat[h][1], lj = t.combos[k][h];
          col *= (idx === L - 1) ? -1.0 : (idx === lj ? 1.0 : 0.0);
        }
        row.push(col);
      }
    }
    return row;
  }
  function backTransform(tr, z) {
    if (!tr) return z;
    var v;
    if (tr.name === "none") v = z;
    else if (tr.name === "log10") v = Math.pow(10, z);
    else if (tr.lam === 0) v = Math.exp(z);
    else {
      var ok = tr.lam > 0 ? z >= 0 : z > 0;
      v = ok ? Math.pow(Math.abs(z), 1.0 / tr.lam) : NaN;
    }
    return v - tr.constant;
  }
  function rowAt(m, setting) {
    return modelRow(m, m.factors.map(function (f) { return encode(f, setting[f.name], m.coded_decimals); }));
  }
  function fitted(m, x) { var y = 0.0; for (var i = 0; i < x.length; i++) y += x[i] * m.b[i]; return y; }
  /* a Gaussian process (GPResult.kriging_form): r = variance R(x, X), one entry per run */
  var SQRT5 = Math.sqrt(5.0), SQRT3 = Math.sqrt(3.0);
  function krigingCross(m, setting) {
    var g = m.kriging, xc = m.factors.map(function (f) { return encode(f, setting[f.name], null); });
    var n = g.x.length, k = xc.length, r = new Array(n);
    for (var i = 0; i < n; i++) {
      var xi = g.x[i], tot = 0.0, poly = 1.0;
      for (var j = 0; j < k; j++) {
        var h = xc[j] - xi[j];
        if (g.kernel === "gauss") { h = h / g.length_scales[j]; tot += h * h; continue; }
        var a = Math.abs(h) * (g.kernel === "matern52" ? SQRT5 : SQRT3) / g.length_scales[j];
        tot += a;
        poly *= g.kernel === "matern52" ? 1.0 + a * (1.0 + a / 3.0) : 1.0 + a;
      }
      r[i] = g.variance * (g.kernel === "gauss" ? Math.exp(-0.5 * tot) : Math.exp(-tot) * poly);
    }
    return r;
  }
  function dot(a, b) { var s = 0.0; for (var i = 0; i < a.length; i++) s += a[i] * b[i]; return s; }
  function krigingMean(m, setting) {
    return fitted(m, rowAt(m, setting)) + dot(krigingCross(m, setting), m.kriging.alpha);
  }
  /* mean and variance of the mean, as GPResult.predict: v = L^-1 r, w = r_f^-T (f - ft' v),
   * var = variance - v.v + w.w */
  function krigingPredict(m, setting) {
    var g = m.kriging, f = rowAt(m, setting), r = krigingCross(m, setting), n = r.length, p = f.length;
    var v = new Array(n);
    for (var i = 0; i < n; i++) {
      var s = r[i], Li = g.L[i];
      for (var j = 0; j < i; j++) s -= Li[j] * v[j];
      v[i] = s / Li[i];
    }
    var u = new Array(p);
    for (var a = 0; a < p; a++) { var t = f[a]; for (var q = 0; q < n; q++) t -= g.ft[q][a] * v[q]; u[a] = t; }
    var w = new Array(p);
    for (var b = 0; b < p; b++) {  /* r_f' w = u, r_f upper triangular */
      var z = u[b];
      for (var c = 0; c < b; c++) z -= g.r_f[c][b] * w[c];
      w[b] = z / g.r_f[b][b];
    }
    var y = fitted(m, f) + dot(r, g.alpha);
    var vm = Math.max(g.variance - dot(v, v) + dot(w, w), 0.0), se = Math.sqrt(vm);
    var hm = m.t * se, hn = m.t * Math.sqrt(vm + g.nugget);
    return {predicted: y, se: se, ci_low: y - hm, ci_high: y + hm, pi_low: y - hn, pi_high: y + hn};
  }
  /* the prediction alone, on the response's own scale (no intervals: what a search needs) */
  function predictValue(m, setting) {
    if (m.kriging) return krigingMean(m, setting);
    var y = fitted(m, rowAt(m, setting));
    return m.transform ? backTransform(m.transform, y) : y;
  }
  /* x' M x */
  function quad(M, x) {
    var n = x.length, q = 0.0;
    for (var a = 0; a < n; a++) {
      var s = 0.0, Ma = M[a];
      for (var b = 0; b < n; b++) s += Ma[b] * x[b];
      q += x[a] * s;
    }
    return q;
  }
  /* log Gamma (Lanczos, g = 7, n = 9: relative error below 1e-15 for x > 0) */
  var LANCZOS = [0.99999999999980993, 676.5203681218851, -1259.1392167224028, 771.32342877765313,
                 -176.61502916214059, 12.507343278686905, -0.13857109526572012, 9.9843695780195716e-6,
                 1.5056327351493116e-7];
  function lgamma(x) {
    if (x < 0.5) return Math.log(Math.PI / Math.abs(Math.sin(Math.PI * x))) - lgamma(1 - x);
    x -= 1;
    var a = LANCZOS[0], t = x + 7.5;
    for (var i = 1; i < 9; i++) a += LANCZOS[i] / (x + i);
    return 0.5 * Math.log(2 * Math.PI) + (x + 0.5) * Math.log(t) - t + Math.log(a);
  }
  /* regularised incomplete beta I_x(a, b) by its continued fraction (modified Lentz) */
  function betacf(a, b, x) {
    var TINY = 1e-300, c = 1.0, d = 1.0 - (a + b) * x / (a + 1);
    if (Math.abs(d) < TINY) d = TINY;
    d = 1.0 / d;
    var h = d;
    for (var m = 1; m <= 10000; m++) {
      var m2 = 2 * m, aa = m * (b - m) * x / ((a + m2 - 1) * (a + m2));
      d = 1.0 + aa * d; if (Math.abs(d) < TINY) d = TINY; c = 1.0 + aa / c; if (Math.abs(c) < TINY) c = TINY;
      d = 1.0 / d; h *= d * c;
      aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1));
      d = 1.0 + aa * d; if (Math.abs(d) < TINY) d = TINY; c = 1.0 + aa / c; if (Math.abs(c) < TINY) c = TINY;
      d = 1.0 / d;
      var del = d * c;
      h *= del;
      if (Math.abs(del - 1.0) < 1e-16) break;
    }
    return h;
  }
  function ibeta(a, b, x) {
    if (x <= 0) return 0.0;
    if (x >= 1) return 1.0;
    var lbt = lgamma(a + b) - lgamma(a) - lgamma(b) + a * Math.log(x) + b * Math.log1p(-x);
    if (x < (a + 1) / (a + b + 2)) return Math.exp(lbt) * betacf(a, b, x) / a;
    return 1.0 - Math.exp(lbt) * betacf(b, a, 1 - x) / b;
  }
  /* upper tail P(T > t) of Student's t with df degrees of freedom, t >= 0 */
  function tUpper(t, df) {
    var x = df / (df + t * t);
    return x < 0.5 ? 0.5 * ibeta(df / 2, 0.5, x) : 0.5 * (1.0 - ibeta(0.5, df / 2, t * t / (df + t * t)));
  }
  /* the quantile t(p, df) for p > 0.5 (any real df > 0): bisection to a bracket, then Newton
   * on the tail (the density in closed form); what FitResult.predict takes from SciPy's stdtrit */
  function tQuantile(df, p) {
    if (!(df > 0) || !isFinite(df)) return df === Infinity ? tQuantile(1e300, p) : NaN;
    var tail = 1.0 - p, lo = 0.0, hi = 1.0;
    while (tUpper(hi, df) > tail && hi < 1e300) { lo = hi; hi *= 2; }
    var t = 0.5 * (lo + hi);
    var logc = lgamma((df + 1) / 2) - lgamma(df / 2) - 0.5 * Math.log(df * Math.PI);
    for (var i = 0; i < 200; i++) {
      var f = tUpper(t, df) - tail;
      if (f > 0) lo = t; else hi = t;
      var dens = Math.exp(logc - (df + 1) / 2 * Math.log1p(t * t / df));
      var next = t + f / dens;
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (Math.abs(next - t) <= 1e-15 * Math.abs(next)) { t = next; break; }
      t = next;
    }
    return t;
  }
  /* setting: {factor name: actual value or level}; returns predicted, se, ci, pi, computed as
   * FitResult.predict computes them from the model's interval form (rsm_lrg.model.contract.prediction):
   * se² = x'·cov_se·x, var_mean = x'·cov_mean·x, var_new = var_mean + s2_new, and the t
   * quantile at the fit's df (OLS: embedded) or at the Kenward-Roger df of x (REML) */
  function predict(m, setting) {
    if (m.kriging) return krigingPredict(m, setting);
    var x = rowAt(m, setting), f = m.interval;
    var y = fitted(m, x);
    var se2 = quad(f.cov_se, x), vm = quad(f.cov_mean, x);
    var s2new = f.s2_new === null ? NaN : f.s2_new;
    var tq;
    if (f.kr) {
      var a = f.kr.phi_p_phi.map(function (M) { return quad(M, x); }), A2 = 0.0;
      for (var r = 0; r < a.length; r++) for (var q = 0; q < a.length; q++) A2 += f.kr.w[r][q] * a[r] * a[q];
      var su = se2 / (f.kr.unit || 1.0);  /* w is in units of kr.unit² (a response in any unit) */
      A2 /= su * su;
      tq = se2 > 0 ? tQuantile(A2 > 0 ? 2.0 / A2 : Infinity, 1 - (1 - m.confidence) / 2) : NaN;
    } else {
      tq = m.t === null ? NaN : m.t;
    }
    var se = Math.sqrt(Math.max(se2, 0)), hm = tq * Math.sqrt(vm), hn = tq * Math.sqrt(vm + s2new);
    var out = {predicted: y, se: se, ci_low: y - hm, ci_high: y + hm, pi_low: y - hn, pi_high: y + hn};
    if (m.transform) {
      var tr = m.transform;
      out.predicted_transformed = y;
      out.predicted = backTransform(tr, y);
      [["ci_low", "ci_high"], ["pi_low", "pi_high"]].forEach(function (p) {
        var u = backTransform(tr, out[p[0]]), w = backTransform(tr, out[p[1]]);
        out[p[0]] = Math.min(u, w); out[p[1]] = Math.max(u, w);
        if (isNaN(u) || isNaN(w)) { out[p[0]] = NaN; out[p[1]] = NaN; }
      });
    }
    return out;
  }

  // -- the setting --------------------------------------------------------------------------
  var ctl = dict();   /* name -> control element */
  var txt = dict();   /* name -> number box */
  document.querySelectorAll("[data-factor]").forEach(function (el) { ctl[el.getAttribute("data-factor")] = el; });
  document.querySelectorAll("[data-factor-text]").forEach(function (el) { txt[el.getAttribute("data-factor-text")] = el; });

  function setting() {
    var s = dict();
    CONTROLS.forEach(function (c) {
      var el = ctl[c.name];
      s[c.name] = c.kind === "categoric" ? el.value : parseFloat(el.value);
    });
    return s;
  }

  // -- a mixture: the blend stays on the simplex and inside the bounds ------------------------
  var COMP = MIX ? MIX.components : [];
  var COMP_NAMES = COMP.map(function (c) { return c.name; });
  function isComponent(name) { return COMP_NAMES.indexOf(name) >= 0; }
  /* The blend after component `name` is set to v: v is clamped to what the others' bounds
     allow, the others share the rest in proportion to their current amounts (JMP's mixture
     profiler; the Cox direction), a component pushed past a bound is held there and the rest
     shared again among the others; the residue of the sum (round-off) goes to the component
     with the most room, so the blend sums to the total exactly. */
  function rebalance(s, name, v) {
    var T = MIX.total, out = copy(s), me = COMP[COMP_NAMES.indexOf(name)];
    var others = COMP.filter(function (c) { return c.name !== name; });
    var sumLo = 0, sumHi = 0, old = 0;
    others.forEach(function (c) { sumLo += c.lower; sumHi += c.upper; old += s[c.name]; });
    v = Math.min(Math.min(me.upper, T - sumLo), Math.max(Math.max(me.lower, T - sumHi), v));
    out[name] = v;
    var free = others.slice(), fixed = 0, rest = T - v;
    for (var it = 0; it <= others.length && free.length; it++) {
      var w = 0;
      free.forEach(function (c) { w += old > 0 ? s[c.name] : 1; });
      var avail = rest - fixed, viol = [];
      free.forEach(function (c) {
        var share = w > 0 ? (old > 0 ? s[c.name] : 1) / w : 1 / free.length;
        out[c.name] = avail * share;
        if (out[c.name] < c.lower || out[c.name] > c.upper) viol.push(c);
      });
      if (!viol.length) break;
      viol.forEach(function (c) { out[c.name] = Math.min(c.upper, Math.max(c.lower, out[c.name])); fixed += out[c.name]; });
      free = free.filter(function (c) { return viol.indexOf(c) < 0; });
    }
    var sum = 0;
    COMP.forEach(function (c) { sum += out[c.name]; });
    var resid = T - sum;
    if (resid !== 0) {
      var best = null, room = -Infinity;
      others.forEach(function (c) {
        var r = resid > 0 ? c.upper - out[c.name] : out[c.name] - c.lower;
        if (r > room) { room = r; best = c; }
      });
      if (best) out[best.name] = out[best.name] + resid;
    }
    return out;
  }
  /* coded setting of the first model (components as L-pseudo components) */
  function codedOf(s) {
    var m = MODELS[0];
    return m.factors.map(function (f) { return encode(f, s[f.name], m.coded_decimals); });
  }
  /* whether a setting lies in the region of the bounds and constraints (rows G x <= h, coded) */
  function inRegion(s) {
    var x = codedOf(s);
    for (var r = 0; r < MIX.h.length; r++) {
      var g = MIX.G[r], v = 0;
      for (var j = 0; j < x.length; j++) v += g[j] * x[j];
      if (v - MIX.h[r] > 1e-9 * (1 + Math.abs(MIX.h[r]))) return false;
    }
    return true;
  }
  var H3 = Math.sqrt(3) / 2;
  function ternaryPicks() {
    var ids = ["ternary-a", "ternary-b", "ternary-c"], out = [];
    ids.forEach(function (id, k) {
      var el = document.getElementById(id);
      out.push(el ? el.value : COMP_NAMES[k]);
    });
    return out;
  }
  /* the triangle of three components (top a, left b, right c) on a regular x-y grid: at (x, y)
     the three take the shares fa = y / (sqrt(3)/2), fc = x - fa/2, fb = 1 - fa - fc of what the
     held components leave (S); z is null outside the triangle and outside the region */
  function ternaryGrid(s, fn, n) {
    var picks = ternaryPicks();
    if (picks[0] === picks[1] || picks[0] === picks[2] || picks[1] === picks[2]) return null;
    var S = MIX.total, held = [];
    COMP.forEach(function (c) { if (picks.indexOf(c.name) < 0) { S -= s[c.name]; held.push([c.letter + ": " + c.name, s[c.name]]); } });
    n = n || 90;
    var xs = linspace(0, 1, n + 1), ys = linspace(0, H3, Math.round(n * H3) + 1), z = [], inside = 0, total = 0;
    ys.forEach(function (yv) {
      var row = [];
      xs.forEach(function (xv) {
        var fa = yv / H3, fc = xv - fa / 2, fb = 1 - fa - fc;
        if (fa < -1e-12 || fb < -1e-12 || fc < -1e-12) { row.push(null); return; }
        var t = copy(s);
        t[picks[0]] = S * Math.max(fa, 0); t[picks[1]] = S * Math.max(fb, 0); t[picks[2]] = S * Math.max(fc, 0);
        total++;
        if (!inRegion(t)) { row.push(null); return; }
        inside++;
        var v = fn(t);
        row.push(isFinite(v) ? v : null);
      });
      z.push(row);
    });
    return {x: xs, y: ys, z: z, picks: picks, share: S, held: held, inside: inside, total: total};
  }
  function toXY(s, picks, S) {  /* a blend's place on the triangle */
    var fa = s[picks[0]] / S, fc = s[picks[2]] / S;
    return [fc + fa / 2, fa * H3];
  }
  function triangleFurniture(g, traces, annotations) {
    var p = g.picks.map(function (n) { return COMP[COMP_NAMES.indexOf(n)]; });
    traces.push({type: "scatter", mode: "lines", x: [0.5, 0, 1, 0.5], y: [H3, 0, 0, H3], hoverinfo: "skip",
                 line: {color: "#1b1f24", width: 1.5}, showlegend: false, name: "simplex"});
    [0.2, 0.4, 0.6, 0.8].forEach(function (f) {
      var lines = [[[f / 2, f * H3], [1 - f / 2, f * H3]],              /* a = f */
                   [[(1 - f) / 2, (1 - f) * H3], [1 - f, 0]],           /* b = f */
                   [[f, 0], [(1 + f) / 2, (1 - f) * H3]]];               /* c = f */
      lines.forEach(function (L, k) {
        traces.push({type: "scatter", mode: "lines", x: [L[0][0], L[1][0]], y: [L[0][1], L[1][1]], hoverinfo: "skip",
                     line: {color: "rgba(0,0,0,0.22)", width: 0.7}, showlegend: false});
        /* each edge carries one component's scale: a on the right edge, b on the left, c along the bottom */
        var at = k === 0 ? L[1] : L[0];
        annotations.push({x: at[0], y: at[1], text: fmt(g.share * f, 3), showarrow: false, font: {size: 9, color: "#555"},
                          xanchor: k === 0 ? "left" : (k === 1 ? "right" : "center"), yanchor: k === 2 ? "top" : "middle"});
      });
    });
    annotations.push({x: 0.5, y: H3, text: esc(p[0].letter + ": " + p[0].name), showarrow: false, yanchor: "bottom", font: {size: 12}});
    annotations.push({x: 0, y: 0, text: esc(p[1].letter + ": " + p[1].name), showarrow: false, yanchor: "top", xanchor: "center", yshift: -12, font: {size: 12}});
    annotations.push({x: 1, y: 0, text: esc(p[2].letter + ": " + p[2].name), showarrow: false, yanchor: "top", xanchor: "center", yshift: -12, font: {size: 12}});
    var note = [];
    if (g.held.length) note.push("Slice: " + g.held.map(function (h) { return esc(h[0]) + " = " + fmt(h[1], 4); }).join(", ") +
                                 "; the three share " + fmt(g.share, 4));
    MIX.process.forEach(function (nm) { note.push(esc(nm) + " = " + fmt(setting()[nm], 4)); });
    if (note.length) annotations.push({xref: "paper", yref: "paper", x: 0, y: 1.06, xanchor: "left", showarrow: false,
                                       text: note.join("; "), font: {size: 10, color: "#333"}});
  }
  /* new axis objects for every draw: Plotly writes the domain it computes into the layout it is
     given, and a shared object would carry one figure's domain into the next */
  function triAxes() {
    return {xaxis: {visible: false, range: [-0.08, 1.08], fixedrange: true, constrain: "domain"},
            yaxis: {visible: false, range: [-0.12, H3 + 0.08], scaleanchor: "x", fixedrange: true, constrain: "domain"}};
  }
  function runPoints(g) {  /* the runs on this slice (every run when there are three components) */
    var xs = [], ys = [];
    MIX.points.forEach(function (row) {
      var t = dict(), onSlice = true, S = 0;
      COMP.forEach(function (c, k) { t[c.name] = row[k]; });
      COMP.forEach(function (c) {
        if (g.picks.indexOf(c.name) >= 0) S += t[c.name];
        else if (Math.abs(t[c.name] - setting()[c.name]) > 1e-9 * MIX.total) onSlice = false;
      });
      if (!onSlice || !(S > 0)) return;
      var p = toXY(t, g.picks, S); xs.push(p[0]); ys.push(p[1]);
    });
    return {x: xs, y: ys};
  }
  function drawTernary(s) {
    var el = document.getElementById("ternary-plot"), el3 = document.getElementById("ternary-surface");
    if (!el || !MIX) return;
    var m = MODELS[parseInt((document.getElementById("ternary-response") || {}).value, 10) || 0];
    var g = ternaryGrid(s, function (t) { return predictValue(m, t); });
    if (!g) { Plotly.purge(el); if (el3) Plotly.purge(el3); return; }
    var zl = esc(m.response), traces = [], ann = [];
    traces.push({type: "contour", x: g.x, y: g.y, z: g.z, colorscale: "Viridis", connectgaps: false, name: zl,
                 contours: {showlabels: true, labelformat: ".4~g"},
                 colorbar: {title: {text: zl}, exponentformat: "power", len: 0.75, thickness: 14},
                 hoverinfo: "skip", meta: {kind: "ternary-contour", response: m.response, components: g.picks,
                 share: g.share}});
    triangleFurniture(g, traces, ann);
    var pts = runPoints(g);
    traces.push({type: "scatter", mode: "markers", x: pts.x, y: pts.y, name: "runs", showlegend: false,
                 marker: {symbol: "circle-open", size: 8, color: "#a11d1d", line: {width: 1.5}}, hoverinfo: "skip"});
    var cur = toXY(s, g.picks, g.share), pc = predict(m, s).predicted;
    traces.push({type: "scatter", mode: "markers", x: [cur[0]], y: [cur[1]], name: "current blend", showlegend: false,
                 marker: {size: 10, color: "#a11d1d"},
                 text: [g.picks.map(function (n) { return esc(n) + " = " + fmt(s[n]); }).join("<br>") + "<br>" + zl + " = " + fmt(pc)],
                 hovertemplate: "%{text}<extra></extra>"});
    Plotly.react(el, traces, Object.assign({margin: {l: 20, r: 20, t: 40, b: 30}, showlegend: false,
                                            annotations: ann}, triAxes()), CONFIG);
    if (!el3) return;
    var keep = el3.layout && el3.layout.scene && el3.layout.scene.camera;
    var p = g.picks.map(function (n) { return COMP[COMP_NAMES.indexOf(n)]; });
    var zmin = Infinity;
    g.z.forEach(function (r) { r.forEach(function (v) { if (v !== null && v < zmin) zmin = v; }); });
    Plotly.react(el3, [
      {type: "surface", x: g.x, y: g.y, z: g.z, colorscale: "Viridis", showscale: false, name: zl, hoverinfo: "skip",
       meta: {kind: "ternary-surface", response: m.response, components: g.picks, share: g.share}},
      {type: "scatter3d", mode: "lines", x: [0.5, 0, 1, 0.5], y: [H3, 0, 0, H3], z: [zmin, zmin, zmin, zmin],
       line: {color: "#1b1f24", width: 3}, hoverinfo: "skip", name: "simplex"},
      {type: "scatter3d", mode: "text", x: [0.5, 0, 1], y: [H3 + 0.06, -0.06, -0.06], z: [zmin, zmin, zmin],
       text: p.map(function (c) { return esc(c.letter + ": " + c.name); }), hoverinfo: "skip", name: "corners"},
      {type: "scatter3d", mode: "markers", x: [cur[0]], y: [cur[1]], z: [pc], marker: {size: 5, color: "#a11d1d"},
       name: "current blend", hoverinfo: "skip"}],
      {margin: {l: 0, r: 0, t: 10, b: 0}, showlegend: false, uirevision: "keep",
       scene: {aspectmode: "manual", aspectratio: {x: 1, y: H3, z: 0.7},
               xaxis: {visible: false}, yaxis: {visible: false}, zaxis: axis(zl),
               camera: keep || {eye: {x: -0.9, y: -1.6, z: 0.9}, up: {x: 0, y: 0, z: 1}}}}, CONFIG);
  }
  function drawTernaryOverlay(s) {
    var el = document.getElementById("ternary-overlay");
    if (!el || !MIX) return;
    var g = ternaryGrid(s, function (t) {
      var mt = margin(t);
      return mt === Infinity ? 1 : (!isFinite(mt) ? -1 : Math.max(-1, Math.min(1, mt)));
    }, 80);
    var out = document.getElementById("ternary-overlay-readout");
    if (!g) { Plotly.purge(el); if (out) out.textContent = "Choose three different components."; return; }
    var traces = [{type: "contour", x: g.x, y: g.y, z: g.z, zmin: -1, zmax: 1, showscale: false, connectgaps: false,
                   contours: {start: 0, end: 0, size: 1, coloring: "fill", showlines: false},
                   colorscale: [[0, "rgba(210,210,210,0.6)"], [0.5, "rgba(210,210,210,0.6)"], [0.5, "rgba(240,200,0,0.6)"],
                                [1, "rgba(240,200,0,0.6)"]], hoverinfo: "skip", name: "inside every limit",
                   meta: {kind: "ternary-overlay", components: g.picks, share: g.share}}];
    var ann = [];
    MODELS.forEach(function (m, k) {
      var lim = limitsOf(m);
      var gz = null;
      [0, 1].forEach(function (e) {
        if (!isFinite(lim[e])) return;
        gz = gz || ternaryGrid(s, function (t) { return predictValue(m, t); }, 80);
        traces.push({type: "contour", x: gz.x, y: gz.y, z: gz.z, showscale: false, hoverinfo: "skip", connectgaps: false,
                     contours: {coloring: "none", start: lim[e], end: lim[e], size: 1, showlabels: true, labelformat: ".4~g"},
                     line: {color: COLORS[k % COLORS.length], width: 2, dash: e ? "solid" : "dash"},
                     name: esc(m.response + (e ? " high limit" : " low limit"))});
      });
    });
    triangleFurniture(g, traces, ann);
    var cur = toXY(s, g.picks, g.share);
    traces.push({type: "scatter", mode: "markers", x: [cur[0]], y: [cur[1]], name: "current blend",
                 marker: {symbol: "circle-open", size: 12, color: "#1b1f24", line: {width: 2}}});
    var n = 0;
    g.z.forEach(function (r) { r.forEach(function (v) { if (v !== null && v >= 0) n++; }); });
    if (out) out.textContent = "Inside every limit: " + fmt(100 * n / Math.max(g.inside, 1), 3) + " % of the region's grid points on this triangle. The current blend is " +
      (inside(s) ? "inside." : "outside.");
    Plotly.react(el, traces, Object.assign({margin: {l: 20, r: 20, t: 40, b: 30}, showlegend: false, annotations: ann},
                                           triAxes()), CONFIG);
  }
  function drawTrace() {
    var el = document.getElementById("trace-plot");
    if (!el || !MIX) return;
    var k = parseInt((document.getElementById("ternary-response") || {}).value, 10) || 0;
    var tr = MIX.traces[k], traces = [];
    tr.curves.forEach(function (c, i) {
      traces.push({type: "scatter", mode: "lines", x: c.deviation, y: c.predicted, name: esc(c.letter + ": " + c.name),
                   line: {color: COLORS[i % COLORS.length], width: 2},
                   meta: {kind: "trace", response: tr.response, component: c.name, direction: tr.direction},
                   text: c.deviation.map(function (d, j) { return esc(c.name) + ": \u0394 = " + fmt(d) + "<br>" + esc(tr.response) + " = " + fmt(c.predicted[j]); }),
                   hovertemplate: "%{text}<extra></extra>"});
    });
    Plotly.react(el, traces, {margin: {l: 70, r: 20, t: 20, b: 60}, showlegend: true, legend: {orientation: "h", y: -0.2},
                              xaxis: axis("Deviation from the reference blend (" + (tr.direction === "cox" ? "real proportion" : "L-pseudo units") + ")"),
                              yaxis: axis(esc(tr.response)),
                              shapes: [{type: "line", xref: "x", yref: "paper", x0: 0, x1: 0, y0: 0, y1: 1,
                                        line: {color: "#888", width: 1, dash: "dot"}}]}, CONFIG);
  }
  function shq(s) {
    s = String(s);
    return /^[A-Za-z0-9_.,:=+\-\/@%]+$/.test(s) ? s : "'" + s.replace(/'/g, "'\\''") + "'";
  }
  function settingText(s) {
    return CONTROLS.map(function (c) { return "--at " + shq(c.name + "=" + String(s[c.name])); }).join(" ");
  }

  var rows = dict();
  document.querySelectorAll("[data-prediction]").forEach(function (el) { rows[el.getAttribute("data-response")] = el; });

  function showPredictions(s) {
    MODELS.forEach(function (m) {
      var el = rows[m.response];
      if (!el) return;
      var p = predict(m, s);
      el.setAttribute("data-value", String(p.predicted));
      el.setAttribute("data-ci-low", String(p.ci_low));
      el.setAttribute("data-ci-high", String(p.ci_high));
      el.setAttribute("data-pi-low", String(p.pi_low));
      el.setAttribute("data-pi-high", String(p.pi_high));
      el.querySelector(".pred-value").textContent = fmt(p.predicted, 5);
      el.querySelector(".pred-ci").textContent = fmt(p.ci_low, 4) + " \u2026 " + fmt(p.ci_high, 4);
      el.querySelector(".pred-pi").textContent = fmt(p.pi_low, 4) + " \u2026 " + fmt(p.pi_high, 4);
    });
    document.getElementById("setting-text").textContent = settingText(s);
  }

  // -- figures (drawn on the next animation frame, at most once a frame) --------------------
  var hasPlotly = typeof window.Plotly !== "undefined";
  var CONFIG = {displaylogo: false, responsive: true, modeBarButtonsToRemove: ["sendDataToCloud"]};
  function linspace(a, b, n) {
    var out = [];
    for (var i = 0; i < n; i++) out.push(i === n - 1 ? b : a + (b - a) * i / (n - 1));
    return out;
  }

  var STACK_BELOW_PX = 600, profileStacked = null;
  function drawProfiles(s) {
    var el = document.getElementById("profile-plot");
    if (!el) return;
    /* a narrow screen stacks the panels, one per row (each with its own axis titles) */
    var R = MODELS.length, K = CONTROLS.length, traces = [], stacked = el.clientWidth < STACK_BELOW_PX;
    profileStacked = stacked;
    var layout = stacked ? {
      grid: {rows: R * K, columns: 1, pattern: "independent", ygap: 0.35},
      showlegend: false, margin: {l: 60, r: 10, t: 10, b: 50}, height: 250 * R * K + 60, shapes: []} : {
      grid: {rows: R, columns: K, pattern: "independent", xgap: 0.2, ygap: 0.2},
      showlegend: false, margin: {l: 60, r: 10, t: 20, b: 50}, height: Math.max(300, 220 * R + 60), shapes: []};
    MODELS.forEach(function (m, r) {
      CONTROLS.forEach(function (c, k) {
        var n = r * K + k + 1, xa = "x" + (n === 1 ? "" : n), ya = "y" + (n === 1 ? "" : n);
        var xs, lo = [], hi = [], ys = [];
        var pts = c.kind === "categoric" ? c.levels.slice() : linspace(c.low, c.high, 41);
        pts.forEach(function (v) {
          var t = c.component ? rebalance(s, c.name, v) : copy(s);
          if (!c.component) t[c.name] = v;
          var p = predict(m, t); ys.push(p.predicted); lo.push(p.ci_low); hi.push(p.ci_high);
        });
        xs = pts.map(function (v) { return c.kind === "categoric" ? esc(v) : v; });
        var cur = predict(m, s), xn = esc(c.name), yn = esc(m.response);
        /* hover labels in the page's number format (not Plotly's own) */
        var tip = pts.map(function (v, i) {
          return xn + " = " + (c.kind === "categoric" ? esc(v) : fmt(v)) + "<br>" + yn + " = " + fmt(ys[i]) +
                 "<br>CI " + fmt(lo[i]) + " \u2026 " + fmt(hi[i]);
        });
        var HOVER = "%{text}<extra></extra>";
        if (c.kind === "categoric") {
          traces.push({x: xs, y: ys, type: "scatter", mode: "markers", xaxis: xa, yaxis: ya, marker: {size: 9, color: "#1f4e79"},
                       text: tip, hovertemplate: HOVER,
                       error_y: {type: "data", symmetric: false,
                                 array: hi.map(function (h, i) { return h - ys[i]; }),
                                 arrayminus: lo.map(function (l, i) { return ys[i] - l; })}});
        } else {
          traces.push({x: xs, y: lo, type: "scatter", mode: "lines", line: {width: 0}, xaxis: xa, yaxis: ya,
                       hoverinfo: "skip"});
          traces.push({x: xs, y: hi, type: "scatter", mode: "lines", line: {width: 0}, fill: "tonexty",
                       fillcolor: "rgba(31,78,121,0.18)", xaxis: xa, yaxis: ya, hoverinfo: "skip"});
          traces.push({x: xs, y: ys, type: "scatter", mode: "lines", line: {color: "#1f4e79", width: 2},
                       xaxis: xa, yaxis: ya, text: tip, hovertemplate: HOVER});
        }
        traces.push({x: [c.kind === "categoric" ? esc(s[c.name]) : s[c.name]], y: [cur.predicted], type: "scatter",
                     mode: "markers", marker: {color: "#a11d1d", size: 8}, xaxis: xa, yaxis: ya, hovertemplate: HOVER,
                     text: [xn + " = " + (c.kind === "categoric" ? esc(s[c.name]) : fmt(s[c.name])) + "<br>" + yn + " = " +
                            fmt(cur.predicted) + " (current setting)"]});
        if (c.kind === "numeric") {
          layout.shapes.push({type: "line", xref: xa, yref: ya + " domain", x0: s[c.name], x1: s[c.name],
                              y0: 0, y1: 1, line: {color: "#a11d1d", width: 1, dash: "dot"}});
        }
        var ax = n === 1 ? "" : n;
        layout["xaxis" + ax] = axis(stacked || r === R - 1 ? esc(c.letter + ": " + c.name) : "");
        layout["yaxis" + ax] = axis(stacked || k === 0 ? esc(m.response) : "");
      });
    });
    Plotly.react(el, traces, layout, CONFIG);
  }

  var LIM = dict();  /* response -> [low input, high input], matched by the attribute's value (no selector built from user text) */
  document.querySelectorAll("[data-limit-low]").forEach(function (el) { (LIM[el.getAttribute("data-limit-low")] = LIM[el.getAttribute("data-limit-low")] || [])[0] = el; });
  document.querySelectorAll("[data-limit-high]").forEach(function (el) { (LIM[el.getAttribute("data-limit-high")] = LIM[el.getAttribute("data-limit-high")] || [])[1] = el; });
  /* a limit box shows its number in the page's format (4 figures); until it is edited, the
     limit is the unrounded value it was written with (data-exact) */
  function limitValue(el) {
    if (!el || el.value === "") return NaN;
    var exact = el.getAttribute("data-exact");
    return exact && el.value === el.defaultValue ? parseFloat(exact) : parseFloat(el.value);
  }
  function limitsOf(m) {
    var pair = LIM[m.response] || [];
    var lo = pair[0], hi = pair[1];
    return [limitValue(lo), limitValue(hi)];
  }
  function inside(s) {
    if (!inStudyRegion(s)) return false;
    for (var i = 0; i < MODELS.length; i++) {
      var lim = limitsOf(MODELS[i]), y = predictValue(MODELS[i], s);
      if (!isFinite(y)) return false;
      if (isFinite(lim[0]) && y < lim[0]) return false;
      if (isFinite(lim[1]) && y > lim[1]) return false;
    }
    return true;
  }
  function control(name) { for (var i = 0; i < CONTROLS.length; i++) if (CONTROLS[i].name === name) return CONTROLS[i]; }
  function pairOf(xid, yid) {
    var xs = document.getElementById(xid), ys = document.getElementById(yid);
    return xs && ys ? [control(xs.value), control(ys.value)] : null;
  }
  // -- the setting deepest inside every limit -------------------------------------------------
  function scaleOf(m) {  /* a response's observed range (1 when it has none) */
    var o = m.observed || [], w = (o.length === 2 && o[0] !== null && o[1] !== null) ? o[1] - o[0] : NaN;
    return isFinite(w) && w > 0 ? w : 1.0;
  }
  /* The smallest margin of the predictions to their limits, each in units of its response's
     observed range: >= 0 exactly where inside() holds, < 0 outside, +Infinity with no limit set;
     -Infinity outside the --constraint/--bound region, so no search or shading leaves it. */
  function margin(s) { return inStudyRegion(s) ? limitMargin(s) : -Infinity; }
  function limitMargin(s) {
    var worst = Infinity;
    for (var i = 0; i < MODELS.length; i++) {
      var m = MODELS[i], lim = limitsOf(m), y = predictValue(m, s), sc = scaleOf(m);
      if (!isFinite(y)) return -Infinity;
      if (isFinite(lim[0])) worst = Math.min(worst, (y - lim[0]) / sc);
      if (isFinite(lim[1])) worst = Math.min(worst, (lim[1] - y) / sc);
    }
    return worst;
  }
  function halton(i, b) { var f = 1, r = 0; while (i > 0) { f /= b; r += f * (i % b); i = Math.floor(i / b); } return r; }
  var PRIMES = [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71, 73, 79, 83, 89, 97];
  var MAX_COMBOS = 256;
  function levelCombos(current) {  /* every combination of the categoric levels (the current ones beyond MAX_COMBOS) */
    var out = [dict()], held = false;
    CONTROLS.forEach(function (c) {
      if (c.kind !== "categoric") return;
      if (out.length * c.levels.length > MAX_COMBOS) {
        held = true;
        out.forEach(function (o) { o[c.name] = current[c.name]; });
        return;
      }
      var next = [];
      out.forEach(function (o) { c.levels.forEach(function (lv) { var t = copy(o); t[c.name] = lv; next.push(t); }); });
      out = next;
    });
    return {combos: out, held: held};
  }
  function rng(seed) {  /* mulberry32: the same directions on every run */
    return function () {
      seed = (seed + 0x6D2B79F5) | 0;
      var t = Math.imul(seed ^ (seed >>> 15), 1 | seed);
      t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
      return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
    };
  }
  /* pattern search from s: the coordinate directions and as many random ones (the margin is a
     minimum of smooth functions, so a ridge can need a diagonal step), each step halved when no
     direction gains, from `step` down to `tol` of each factor's range */
  function climb(s, ms, rand, step, tol) {
    var K = NUMERIC.length;
    while (step > tol && K > 0) {
      var dirs = [];
      for (var k = 0; k < K; k++) { var e = NUMERIC.map(function () { return 0; }); e[k] = 1; dirs.push(e); }
      for (var r = 0; r < K; r++) {
        var d = NUMERIC.map(function () { return 2 * rand() - 1; });
        var nrm = Math.sqrt(d.reduce(function (a, v) { return a + v * v; }, 0)) || 1;
        dirs.push(d.map(function (v) { return v / nrm; }));
      }
      var moved = false;
      dirs.forEach(function (d) {
        [-1, 1].forEach(function (sg) {
          var t = copy(s);
          NUMERIC.forEach(function (c, k) {
            t[c.name] = Math.min(c.high, Math.max(c.low, s[c.name] + sg * step * d[k] * (c.high - c.low)));
          });
          var mt = margin(t);
          if (mt > ms) { s = t; ms = mt; moved = true; }
        });
      });
      if (!moved) step /= 2;
    }
    return {setting: s, margin: ms, step: step};
  }
  /* {setting, margin, held} with the largest margin over the factors' box and every level
     combination: per combination the centre and 256 Halton points, the best three climbed to
     1e-3 of each range; the best three of all those climbed on to 1e-9; null when no limit is set */
  function deepest(current) {
    var lc = levelCombos(current), found = [], rand = rng(12345);
    if (limitMargin(current) === Infinity) return null;  /* no limit set */
    lc.combos.forEach(function (base) {
      var starts = [];
      for (var i = 0; i <= 256; i++) {
        var s = copy(current, base);
        NUMERIC.forEach(function (c, k) {
          s[c.name] = i === 0 ? (c.low + c.high) / 2 : c.low + (c.high - c.low) * halton(i, PRIMES[k % PRIMES.length]);
        });
        starts.push({setting: s, margin: margin(s)});
      }
      starts.sort(function (a, b) { return b.margin - a.margin; });
      starts.slice(0, 3).forEach(function (st) { found.push(climb(st.setting, st.margin, rand, 0.25, 1e-3)); });
    });
    found.sort(function (a, b) { return b.margin - a.margin; });
    var best = null;
    found.slice(0, 3).forEach(function (f) {
      var r = climb(f.setting, f.margin, rand, f.step, 1e-9);
      if (best === null || r.margin > best.margin) best = r;
    });
    if (best) best.held = lc.held;
    return best;
  }
  function goDeepest() {
    var out = document.getElementById("deepest-readout");
    var b = deepest(setting());
    if (b === null) { out.textContent = "Set at least one limit first."; return null; }
    if (b.margin === -Infinity) { out.textContent = "No setting inside the --constraint/--bound region was found."; return null; }
    jumpTo(b.setting);
    var pct = fmt(100 * Math.abs(b.margin), 3) + " % of its observed range";
    out.textContent = (b.margin >= 0
      ? "Moved to the setting deepest inside every limit: the nearest limit is " + pct + " away."
      : "No setting meets every limit; moved to the one that misses them least: by " + pct + ".") +
      (b.held ? " Categoric factors with too many level combinations were held at their current levels." : "");
    return b;
  }

  var GRID = 61;
  function overlayGrid(s) {
    var pair = pairOf("overlay-x", "overlay-y");
    if (!pair || pair[0].name === pair[1].name) return null;
    var fx = pair[0], fy = pair[1], xs = linspace(fx.low, fx.high, GRID), ys = linspace(fy.low, fy.high, GRID);
    var z = [], zm = [], zr = MODELS.map(function () { return []; });
    for (var j = 0; j < ys.length; j++) {
      var row = [], mrow = [], rr = MODELS.map(function () { return []; });
      for (var i = 0; i < xs.length; i++) {
        var t = copy(s); t[fx.name] = xs[i]; t[fy.name] = ys[j];
        row.push(inside(t) ? 1 : 0);
        /* the smallest margin to a limit (each response in units of its observed range): >= 0
           inside every limit; its 0 contour is made of the limits' own contours */
        var mt = margin(t);
        mrow.push(mt === Infinity ? 1 : (mt === -Infinity || !isFinite(mt) ? -1 : Math.max(-1, Math.min(1, mt))));
        MODELS.forEach(function (m, k) { rr[k].push(predictValue(m, t)); });
      }
      z.push(row);
      zm.push(mrow);
      rr.forEach(function (r, k) { zr[k].push(r); });
    }
    return {fx: fx, fy: fy, x: xs, y: ys, z: z, zm: zm, zr: zr};
  }
  var COLORS = ["#1f4e79", "#a11d1d", "#1d6b2f", "#9a5b00", "#5b2a86", "#00707a"];
  function drawOverlay(s) {
    var el = document.getElementById("overlay-plot");
    if (!el) return;
    var g = overlayGrid(s), out = document.getElementById("overlay-readout");
    if (!g) { out.textContent = "Choose two different factors."; Plotly.purge(el); return; }
    /* the region inside every limit, filled up to the 0 contour of the smallest margin: its edge
       follows the limit lines (interpolated on the same grid), not the grid's cells */
    var traces = [{type: "contour", x: g.x, y: g.y, z: g.zm, zmin: -1, zmax: 1, showscale: false,
                   contours: {start: 0, end: 0, size: 1, coloring: "fill", showlines: false},
                   colorscale: [[0, "rgba(255,255,255,0)"], [0.5, "rgba(255,255,255,0)"], [0.5, "rgba(240,200,0,0.55)"],
                                [1, "rgba(240,200,0,0.55)"]],
                   line: {width: 0}, hoverinfo: "skip", name: "inside every limit"}];
    MODELS.forEach(function (m, k) {
      var lim = limitsOf(m);
      [0, 1].forEach(function (e) {
        if (!isFinite(lim[e])) return;
        /* the limit is labelled on its line where fmt writes it plainly, and named with its value
           (fmt) in the legend always */
        traces.push({type: "contour", x: g.x, y: g.y, z: g.zr[k], showscale: false, hoverinfo: "skip",
                     contours: {coloring: "none", start: lim[e], end: lim[e], size: 1, showlabels: plainNumber(lim[e]),
                                labelformat: LABEL_FORMAT},
                     line: {color: COLORS[k % COLORS.length], width: 2, dash: e ? "solid" : "dash"},
                     name: esc(m.response + (e ? " high limit " : " low limit ")) + fmt(lim[e])});
      });
    });
    var opt = DATA.desirability ? DATA.desirability.setting : (MODELS.length && DATA.optima[MODELS[0].response]
      ? DATA.optima[MODELS[0].response].setting : null);
    if (opt) traces.push({type: "scatter", mode: "markers", x: [opt[g.fx.name]], y: [opt[g.fy.name]],
                          marker: {symbol: "star", size: 16, color: "#a11d1d"}, name: "optimum"});
    traces.push({type: "scatter", mode: "markers", x: [s[g.fx.name]], y: [s[g.fy.name]],
                 marker: {symbol: "circle-open", size: 12, color: "#1b1f24", line: {width: 2}}, name: "current setting"});
    var n = 0; g.z.forEach(function (r) { r.forEach(function (v) { n += v; }); });
    out.textContent = "Inside every limit: " + fmt(100 * n / (GRID * GRID), 3) + " % of the " + GRID + " \u00d7 " +
      GRID + " grid. The current setting is " + (inside(s) ? "inside." : "outside.");
    Plotly.react(el, traces, {margin: {l: 70, r: 20, t: 20, b: 60}, showlegend: true,
                              legend: {orientation: "h", y: -0.18},
                              xaxis: axis(esc(g.fx.letter + ": " + g.fx.name)),
                              yaxis: axis(esc(g.fy.letter + ": " + g.fy.name))}, CONFIG);
  }

  // The 3-D surface opens seen from above at an angle (as Design-Expert and JMP open theirs):
  // 30 degrees of elevation, from the low corner of both factors; a user's rotation is kept.
  var SURFACE_CAMERA = {eye: {x: -1.5, y: -1.5, z: 1.22}, up: {x: 0, y: 0, z: 1}, center: {x: 0, y: 0, z: -0.1}};

  function drawSurface(s) {
    var el3 = document.getElementById("surface-plot"), el2 = document.getElementById("contour-plot");
    if (!el3) return;
    var pair = pairOf("surface-x", "surface-y");
    var m = MODELS[parseInt(document.getElementById("surface-response").value, 10) || 0];
    if (!pair || pair[0].name === pair[1].name) { Plotly.purge(el3); Plotly.purge(el2); return; }
    var fx = pair[0], fy = pair[1], xs = linspace(fx.low, fx.high, 31), ys = linspace(fy.low, fy.high, 31), z = [];
    ys.forEach(function (yv) {
      z.push(xs.map(function (xv) { var t = copy(s); t[fx.name] = xv; t[fy.name] = yv; return predictValue(m, t); }));
    });
    var cur = predict(m, s).predicted;
    var xl = esc(fx.letter + ": " + fx.name), yl = esc(fy.letter + ": " + fy.name), zl = esc(m.response);
    var keepCamera = el3.layout && el3.layout.scene && el3.layout.scene.camera;
    var tip = z.map(function (row, j) {
      return row.map(function (v, i) { return xl + " = " + fmt(xs[i]) + "<br>" + yl + " = " + fmt(ys[j]) + "<br>" + zl + " = " + fmt(v); });
    });
    var here = [xl + " = " + fmt(s[fx.name]) + "<br>" + yl + " = " + fmt(s[fy.name]) + "<br>" + zl + " = " + fmt(cur) +
                " (current setting)"];
    Plotly.react(el3, [
      {type: "surface", x: xs, y: ys, z: z, colorscale: "Viridis", showscale: false, name: zl,
       text: tip, hovertemplate: "%{text}<extra></extra>"},
      {type: "scatter3d", mode: "markers", x: [s[fx.name]], y: [s[fy.name]], z: [cur], marker: {size: 5, color: "#a11d1d"},
       name: "current setting", text: here, hovertemplate: "%{text}<extra></extra>"}],
      {margin: {l: 0, r: 0, t: 10, b: 0}, showlegend: false, uirevision: "keep",
       scene: {aspectmode: "cube", xaxis: axis(xl), yaxis: axis(yl), zaxis: axis(zl),
               camera: keepCamera || SURFACE_CAMERA}}, CONFIG);
    var E = labelScale(z), zs = E ? z.map(function (row) { return row.map(function (v) { return v / Math.pow(10, E); }); }) : z;
    Plotly.react(el2, [
      {type: "contour", x: xs, y: ys, z: zs, colorscale: "Viridis", contours: {showlabels: true, labelformat: LABEL_FORMAT},
       colorbar: {title: {text: zl + (E ? " (\u00d7 " + power10(E) + ")" : "")}, exponentformat: "power"}, meta: {scale: E}, text: tip,
       hovertemplate: "%{text}<extra></extra>"},
      {type: "scatter", mode: "markers", x: [s[fx.name]], y: [s[fy.name]], marker: {size: 10, color: "#a11d1d"},
       name: "current setting", text: here, hovertemplate: "%{text}<extra></extra>"}],
      {margin: {l: 70, r: 20, t: 20, b: 60}, showlegend: false, uirevision: "keep",
       xaxis: axis(xl), yaxis: axis(yl)}, CONFIG);
  }

  /* a figure is redrawn when it is on screen (or comes on screen) and out of date */
  var FIGS = {"profile-plot": drawProfiles, "overlay-plot": drawOverlay, "surface-plot": drawSurface,
              "ternary-plot": drawTernary, "ternary-overlay": drawTernaryOverlay, "trace-plot": drawTrace};
  var onScreen = dict(), stale = dict();
  var pending = false;
  function drawFig(id, s) {
    stale[id] = false;
    try { FIGS[id](s); } catch (e) { console.error(e); }
  }
  function drawAll() {  /* every figure, now */
    pending = false;
    if (!hasPlotly) return;
    var s = setting();
    Object.keys(FIGS).forEach(function (id) { drawFig(id, s); });
  }
  function drawVisible() {
    pending = false;
    if (!hasPlotly) return;
    var s = setting();
    Object.keys(FIGS).forEach(function (id) {
      if (onScreen[id] || !("IntersectionObserver" in window)) drawFig(id, s);
    });
  }
  function schedule() {
    Object.keys(FIGS).forEach(function (id) { stale[id] = true; });
    if (pending) return;
    pending = true;
    window.requestAnimationFrame(drawVisible);
  }
  if ("IntersectionObserver" in window) {
    var io = new IntersectionObserver(function (entries) {
      entries.forEach(function (en) {
        var id = en.target.id;  /* the contour sits beside the surface and is drawn with it */
        onScreen[id] = en.isIntersecting;
        if (en.isIntersecting && stale[id] && hasPlotly) drawFig(id, setting());
      });
    });
    Object.keys(FIGS).forEach(function (id) { var el = document.getElementById(id); if (el) io.observe(el); });
  }
  window.addEventListener("beforeprint", drawAll);
  /* a turned phone or a resized window: the profiler's panels are laid out again when they
     change between side by side and stacked */
  window.addEventListener("resize", function () {
    var el = document.getElementById("profile-plot");
    if (el && hasPlotly && profileStacked !== null && (el.clientWidth < STACK_BELOW_PX) !== profileStacked) {
      drawFig("profile-plot", setting());
    }
  });
  function update() {
    var s = setting();
    CONTROLS.forEach(function (c) { if (txt[c.name] && document.activeElement !== txt[c.name]) txt[c.name].value = c.kind === "numeric" ? fmt(s[c.name], 6, "ascii") : String(s[c.name]); });
    showPredictions(s);
    schedule();
  }

  // -- events ----------------------------------------------------------------------------------
  /* the blend last shown: a component's move rescales the others from it */
  var lastBlend = null;
  function setBlend(b) {
    COMP.forEach(function (c) { ctl[c.name].value = String(b[c.name]); });
    lastBlend = copy(b);
  }
  function moveComponent(name, v) {
    var base = copy(setting(), lastBlend || dict());
    setBlend(rebalance(base, name, v));
    update();
  }
  Object.keys(ctl).forEach(function (name) {
    var handler = isComponent(name) ? function () { moveComponent(name, parseFloat(ctl[name].value)); } : update;
    ctl[name].addEventListener("input", handler);
    ctl[name].addEventListener("change", handler);
  });
  Object.keys(txt).forEach(function (name) {
    txt[name].addEventListener("change", function () {
      var v = parseFloat(txt[name].value), c = control(name);
      if (isComponent(name)) { if (isFinite(v)) moveComponent(name, v); else update(); }
      else {
        if (isFinite(v)) { ctl[name].value = String(Math.min(c.high, Math.max(c.low, v))); }
        update();
      }
      /* the box shows the value used (a 5 typed into a 0.4 ... 0.6 box becomes 0.6), focused or not */
      txt[name].value = fmt(setting()[name], 6, "ascii");
    });
  });
  function jumpTo(set) {
    CONTROLS.forEach(function (c) {
      if (!(c.name in set)) return;
      ctl[c.name].value = String(set[c.name]);
    });
    if (MIX) lastBlend = copy(setting());
    update();
  }
  document.querySelectorAll("[data-jump]").forEach(function (b) {
    b.addEventListener("click", function () {
      var kind = b.getAttribute("data-jump");
      if (kind === "center") {
        var set = dict();
        CONTROLS.forEach(function (c) {
          set[c.name] = c.kind === "categoric" ? c.levels[0] : (c.center !== undefined ? c.center : (c.low + c.high) / 2);
        });
        jumpTo(set);
      } else if (kind === "desirability" && DATA.desirability) jumpTo(DATA.desirability.setting);
      else if (kind === "optimum") {
        var o = DATA.optima[b.getAttribute("data-response")];
        if (o) jumpTo(o.setting);
      }
    });
  });
  var deepBtn = document.getElementById("overlay-deepest");
  if (deepBtn) deepBtn.addEventListener("click", goDeepest);
  document.querySelectorAll("[data-limit-low], [data-limit-high], #overlay-x, #overlay-y, #surface-x, #surface-y, #surface-response, " +
                            "#ternary-a, #ternary-b, #ternary-c, #ternary-response")
    .forEach(function (el) { el.addEventListener("input", schedule); el.addEventListener("change", schedule); });
  var pre = document.getElementById("setting-text");
  pre.addEventListener("click", function () {
    var r = document.createRange(); r.selectNodeContents(pre);
    var sel = window.getSelection(); sel.removeAllRanges(); sel.addRange(r);
  });

  /* for scripts that drive the page (tests, notebooks): the page's own arithmetic */
  window.rsmReport = {
    predict: function (response, s) {
      for (var i = 0; i < MODELS.length; i++) if (MODELS[i].response === response) return predict(MODELS[i], s);
      throw new Error("no such response");
    },
    setting: setting, settingText: function () { return settingText(setting()); },
    insideLimits: function (s) { return inside(Object.assign(setting(), s)); },
    overlayGrid: function () { return overlayGrid(setting()); },
    margin: function (s) { return margin(Object.assign(setting(), s)); },
    goDeepest: goDeepest,
    drawNow: drawAll,
    formatNumber: fmt,
    rebalance: function (name, v) { return rebalance(setting(), name, v); },
    ternaryGrid: function () { return MIX ? ternaryGrid(setting(), function (t) { return predictValue(MODELS[0], t); }) : null; },
    limits: function () { return MODELS.map(limitsOf); }
  };
  if (MIX) lastBlend = copy(setting());
  update();
  if (hasPlotly) drawAll();
})();
