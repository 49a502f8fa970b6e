// The force-map report's page: maps, histogram, status filter and the selected curve, drawn
// with plotly.js from the JSON that layerjkr embedded (map_report.hpp describes it).
// window.layerjkr.select(i) shows item i and returns its values keyed by the CSV's columns.
(function () {
  'use strict';
  var D = JSON.parse(document.getElementById('layerjkr-data').textContent);
  var C = D.columns;
  var N = D.count;
  var QUALITIES = ['ok', 'warning', 'not identifiable', 'not converged', 'failed'];
  var COLOUR = {'ok': '#2ca02c', 'warning': '#ff7f0e', 'not identifiable': '#9467bd', 'not converged': '#d62728',
                'failed': '#222222'};
  var SYMBOL = {'warning': 'triangle-up-open', 'not identifiable': 'diamond-open', 'not converged': 'circle-open',
                'failed': 'x-thin-open'};
  var STATUS_FIELD = {key: '__quality', label: 'status', unit: ''};
  var FIELDS = D.fields.concat([STATUS_FIELD]);
  var CONFIG = {displaylogo: false, responsive: false, showLink: false, showSendToCloud: false,
                modeBarButtonsToRemove: ['sendDataToCloud', 'select2d', 'lasso2d']};

  var state = {view: 0, field: FIELDS[0].key, show: {}, selected: -1};
  QUALITIES.forEach(function (q) { state.show[q] = true; });

  // Where each item is drawn: its view and cell.
  var where = new Array(N);
  D.views.forEach(function (v, vi) {
    v.cells.forEach(function (item, cell) { if (item >= 0) where[item] = {view: vi, cell: cell}; });
  });

  var mapDiv = document.getElementById('map'), histDiv = document.getElementById('hist');
  var curveDiv = document.getElementById('curve'), valuesTable = document.getElementById('values');

  function fmt(v, unit) {
    if (v === null || v === undefined) return '\u2013';
    if (typeof v !== 'number') return String(v);
    var a = Math.abs(v);
    var s = Number.isInteger(v) && a < 1e6 ? String(v) : a !== 0 && (a < 1e-3 || a >= 1e6) ? v.toExponential(4) : v.toPrecision(5);
    return unit ? s + ' ' + unit : s;
  }

  // Values in SI units scaled to a prefix chosen from their largest magnitude: {factor, label}
  // with label e.g. 'µm'; the axis then shows plain numbers (no 'u' or 'm' beside '[N]').
  var PREFIXES = [[1e-15, 'f'], [1e-12, 'p'], [1e-9, 'n'], [1e-6, '\u00b5'], [1e-3, 'm'], [1, ''], [1e3, 'k'],
                  [1e6, 'M'], [1e9, 'G']];
  function siScale(arrays, unit) {
    var big = 0;
    arrays.forEach(function (a) { a.forEach(function (x) { if (isFinite(x)) big = Math.max(big, Math.abs(x)); }); });
    var chosen = PREFIXES[5];
    if (big > 0) PREFIXES.forEach(function (p) { if (big >= p[0] * 0.999) chosen = p; });
    return {factor: 1 / chosen[0], label: chosen[1] + unit};
  }
  function scaled(a, s) { return a.map(function (x) { return x * s.factor; }); }

  // Plotly renders hover text as HTML: names and errors are shown as text.
  function escapeHtml(s) {
    return String(s).replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');
  }

  function fieldOf(key) {
    for (var k = 0; k < FIELDS.length; ++k) if (FIELDS[k].key === key) return FIELDS[k];
    throw new RangeError('layerjkr: no field ' + key);
  }

  function value(key, i) {
    return key === STATUS_FIELD.key ? QUALITIES.indexOf(C.quality[i]) : C[key][i];
  }

  // Every pixel keeps its value; the status boxes only toggle the markers drawn over it.
  function visible(i) { return i >= 0; }

  // The cell's x (column) and y (row) in view v.
  function xy(v, cell) { return {x: cell % v.nx, y: Math.floor(cell / v.nx)}; }

  // ---- the map, its histogram and status markers
  function drawMap() {
    var v = D.views[state.view], f = fieldOf(state.field);
    var z = [], text = [], values = [];
    for (var r = 0; r < v.ny; ++r) {
      var zr = [], tr = [];
      for (var c = 0; c < v.nx; ++c) {
        var i = v.cells[r * v.nx + c];
        var val = visible(i) ? value(f.key, i) : null;
        if (val !== null && val !== undefined && f.key !== STATUS_FIELD.key) values.push(val);
        zr.push(val === undefined ? null : val);
        tr.push(i >= 0 ? '#' + i + ' ' + escapeHtml(C.file[i]) + '<br>' + C.quality[i] +
                (C.error[i] ? ': ' + escapeHtml(C.error[i].slice(0, 80)) : '') : 'no curve');
      }
      z.push(zr);
      text.push(tr);
    }
    var heat = {type: 'heatmap', z: z, text: text, hoverongaps: false, name: f.label,
                hovertemplate: '%{text}<br>(%{x}, %{y})<br>' + f.label + ' = %{z:.4g} ' + f.unit + '<extra></extra>',
                colorbar: {title: {text: f.label + (f.unit ? ' [' + f.unit + ']' : ''), side: 'right'},
                           exponentformat: 'SI'}};
    if (f.key === STATUS_FIELD.key) {
      var scale = [];
      QUALITIES.forEach(function (q, k) {
        scale.push([k / QUALITIES.length, COLOUR[q]]);
        scale.push([(k + 1) / QUALITIES.length, COLOUR[q]]);
      });
      heat.colorscale = scale;
      heat.zmin = -0.5;
      heat.zmax = QUALITIES.length - 0.5;
      heat.colorbar.tickvals = QUALITIES.map(function (q, k) { return k; });
      heat.colorbar.ticktext = QUALITIES;
      heat.hovertemplate = '%{text}<br>(%{x}, %{y})<extra></extra>';
    } else {
      heat.colorscale = 'Viridis';
    }
    var traces = [heat];
    // Bad pixels: one marker trace per status (not in the status map itself, which colours them).
    QUALITIES.forEach(function (q) {
      if (q === 'ok' || !state.show[q]) return;
      var xs = [], ys = [];
      v.cells.forEach(function (i, cell) {
        if (i >= 0 && C.quality[i] === q) { var p = xy(v, cell); xs.push(p.x); ys.push(p.y); }
      });
      if (!xs.length) return;
      traces.push({type: 'scatter', mode: 'markers', x: xs, y: ys, name: q + ' (' + xs.length + ')', hoverinfo: 'skip',
                   marker: {symbol: SYMBOL[q], color: f.key === STATUS_FIELD.key ? '#fff' : COLOUR[q],
                            size: Math.max(3, Math.min(9, 0.55 * 380 / Math.max(v.nx, v.ny))), line: {width: 1}},
                   opacity: 0.9});
    });
    var sel = selectedXY();
    traces.push({type: 'scatter', mode: 'markers', x: sel ? [sel.x] : [], y: sel ? [sel.y] : [], name: 'selected',
                 hoverinfo: 'skip', showlegend: false,
                 marker: {symbol: 'square-open', color: '#e00', size: Math.max(8, Math.min(20, 460 / Math.max(v.nx, v.ny))),
                          line: {width: 3}}});
    var layout = {margin: {l: 50, r: 10, t: 30, b: 40}, title: {text: f.label, font: {size: 14}},
                  xaxis: {title: {text: v.kind === 'grid' ? 'grid x' : 'index % ' + v.nx}, range: [-0.5, v.nx - 0.5],
                          dtick: Math.max(1, Math.ceil(v.nx / 8)), constrain: 'domain', showgrid: false, zeroline: false},
                  yaxis: {title: {text: v.kind === 'grid' ? 'grid y' : 'index / ' + v.nx}, scaleanchor: 'x',
                          range: v.kind === 'grid' ? [-0.5, v.ny - 0.5] : [v.ny - 0.5, -0.5], constrain: 'domain',
                          dtick: Math.max(1, Math.ceil(v.ny / 8)),
                          showgrid: false, zeroline: false},
                  legend: {orientation: 'h', y: -0.12}, uirevision: state.view, showlegend: true};
    Plotly.react(mapDiv, traces, layout, CONFIG);
    var histLayout = {margin: {l: 50, r: 10, t: 10, b: 40}, bargap: 0.02,
                      xaxis: {title: {text: f.label + (f.unit ? ' [' + f.unit + ']' : '')}, exponentformat: 'SI'},
                      yaxis: {title: {text: 'curves'}}};
    var hist = f.key === STATUS_FIELD.key
      ? {type: 'bar', x: QUALITIES, y: QUALITIES.map(function (q) { return countOf(v, q); }),
         marker: {color: QUALITIES.map(function (q) { return COLOUR[q]; })}}
      : {type: 'histogram', x: values, marker: {color: '#3b6ea8'}, nbinsx: 40};
    Plotly.react(histDiv, [hist], histLayout, CONFIG);
  }

  function countOf(v, q) {
    var n = 0;
    v.cells.forEach(function (i) { if (i >= 0 && C.quality[i] === q) ++n; });
    return n;
  }

  function selectedXY() {
    var i = state.selected;
    if (i < 0 || !where[i] || where[i].view !== state.view) return null;
    return xy(D.views[state.view], where[i].cell);
  }

  function moveMarker() {
    var sel = selectedXY(), traces = mapDiv.data;
    if (!traces) return;
    Plotly.restyle(mapDiv, {x: [sel ? [sel.x] : []], y: [sel ? [sel.y] : []]}, [traces.length - 1]);
  }

  // ---- the selected curve
  var decoded = {};
  function decode(e) {
    var bin = atob(e.codes), n = bin.length / 2, out = new Array(n), span = e.hi - e.lo;
    for (var k = 0; k < n; ++k) {
      var c = bin.charCodeAt(2 * k) | (bin.charCodeAt(2 * k + 1) << 8);
      out[k] = c === 65535 ? NaN : e.lo + span * c / 65534;
    }
    return out;
  }
  function samplesOf(i) {
    if (!D.curves[i]) return null;
    if (!decoded[i]) {
      var c = D.curves[i];
      var s = {n: c.n, delta: decode(c.delta), P: decode(c.P), P_fit: c.P_fit ? decode(c.P_fit) : null, delta0: c.delta0};
      var ex = s.delta.map(function () { return false; });
      c.excluded.forEach(function (span) { for (var k = span[0]; k <= span[1]; ++k) ex[k] = true; });
      s.excluded = ex;
      decoded[i] = s;
    }
    return decoded[i];
  }

  function drawCurve(i) {
    var s = samplesOf(i), failed = C.status[i] === 'error';
    var layout = {margin: {l: 60, r: 10, t: 40, b: 45}, title: {text: '#' + i + ' ' + escapeHtml(C.file[i]), font: {size: 13}},
                  xaxis: {anchor: 'y2'}, yaxis: {domain: [0.36, 1]}, yaxis2: {domain: [0, 0.27]},
                  legend: {orientation: 'h', y: 1.0, yanchor: 'bottom', x: 1, xanchor: 'right'}, showlegend: true,
                  annotations: []};
    var traces = [];
    if (failed)
      layout.annotations.push({text: 'not fitted: ' + escapeHtml(C.error[i].slice(0, 160)), xref: 'paper', yref: 'paper',
                               x: 0.5, y: 0.97, showarrow: false, font: {color: '#b00'}});
    if (!s) {
      if (!failed)
        layout.annotations.push({text: 'no samples kept for display', xref: 'paper', yref: 'paper', x: 0.5, y: 0.7,
                                 showarrow: false, font: {color: '#b00'}});
    } else if (!s.P_fit) {
      // A curve that failed: its samples as read, against the data's own displacement.
      var xs = siScale([s.delta], 'm'), ys = siScale([s.P], 'N');
      layout.xaxis.title = {text: 'displacement \u03b4 as read [' + xs.label + ']'};
      layout.yaxis.title = {text: 'force [' + ys.label + ']'};
      layout.yaxis.domain = [0, 1];
      delete layout.yaxis2;
      layout.xaxis.anchor = 'y';
      traces.push({type: 'scatter', mode: 'markers', x: scaled(s.delta, xs), y: scaled(s.P, ys), name: 'data (not fitted)',
                   marker: {size: 4, color: '#3b6ea8'}});
    } else {
      // Force against indentation from the model's contact point (the fitted or fixed delta0).
      var d0 = s.delta0 === null || s.delta0 === undefined ? 0 : s.delta0;
      var ind = s.delta.map(function (d) { return d - d0; });
      var res = s.P.map(function (p, k) { return p - s.P_fit[k]; });
      var xsc = siScale([ind], 'm'), ysc = siScale([s.P, s.P_fit], 'N'), rsc = siScale([res], 'N');
      layout.xaxis.title = {text: 'indentation \u03b4 \u2212 \u03b4\u2080 [' + xsc.label + ']'};
      layout.yaxis.title = {text: 'force [' + ysc.label + ']'};
      layout.yaxis2.title = {text: 'residual [' + rsc.label + ']'};
      var inD = [], inP = [], inR = [], exD = [], exP = [], exR = [];
      for (var k = 0; k < ind.length; ++k) {
        var x = ind[k] * xsc.factor, p = s.P[k] * ysc.factor, r = res[k] * rsc.factor;
        if (s.excluded[k]) { exD.push(x); exP.push(p); exR.push(r); }
        else { inD.push(x); inP.push(p); inR.push(r); }
      }
      traces.push({type: 'scatter', mode: 'markers', x: inD, y: inP, name: 'data', marker: {size: 4, color: '#3b6ea8'}});
      if (exD.length)
        traces.push({type: 'scatter', mode: 'markers', x: exD, y: exP, name: 'excluded', marker: {size: 6, symbol: 'x-thin-open', color: '#d62728'}});
      traces.push({type: 'scatter', mode: 'lines', x: scaled(ind, xsc), y: scaled(s.P_fit, ysc), name: 'fit',
                   line: {color: '#ff7f0e', width: 2}});
      traces.push({type: 'scatter', mode: 'markers', x: inD, y: inR, name: 'residual', yaxis: 'y2', showlegend: false,
                   marker: {size: 3, color: '#3b6ea8'}});
      if (exD.length)
        traces.push({type: 'scatter', mode: 'markers', x: exD, y: exR, name: 'excluded residual', yaxis: 'y2',
                     showlegend: false, marker: {size: 5, symbol: 'x-thin-open', color: '#d62728'}});
    }
    if (s)
      layout.annotations.push({text: s.delta.length + ' of ' + s.n + ' samples shown', xref: 'paper', yref: 'paper',
                               x: 0, y: 1.0, yanchor: 'bottom', xanchor: 'left', showarrow: false, font: {size: 11, color: '#666'}});
    Plotly.react(curveDiv, traces, layout, CONFIG);
  }

  function row(name, text, bad) {
    var tr = document.createElement('tr');
    if (bad) tr.className = 'bad';
    var th = document.createElement('th'), td = document.createElement('td');
    th.textContent = name;
    td.textContent = text;
    tr.appendChild(th);
    tr.appendChild(td);
    valuesTable.appendChild(tr);
  }

  function drawValues(i) {
    valuesTable.textContent = '';
    row('curve', '#' + i + '  ' + C.file[i] + (C.curve[i] !== null ? '  (curve ' + C.curve[i] + ')' : ''));
    if (C.grid_x[i] !== null) row('pixel', '(' + C.grid_x[i] + ', ' + C.grid_y[i] + ')  at (' + fmt(C.x[i], 'm') + ', ' + fmt(C.y[i], 'm') + ')');
    row('status', C.quality[i], C.quality[i] !== 'ok');
    if (C.status[i] === 'error') {
      row('error', C.error[i], true);
      return;
    }
    row('model', C.model[i]);
    D.fields.forEach(function (f) {
      if (D.free.indexOf(f.key) < 0) return;
      var e = C[f.key + '_stderr'][i];
      row(f.key, fmt(C[f.key][i]) + (e !== null ? ' \u00b1 ' + fmt(e) : ' (no error bar)') + (f.unit ? ' ' + f.unit : ''));
    });
    row('rms residual', fmt(C.rms_residual[i], 'N'));
    row('converged', (C.converged[i] ? 'yes' : 'no') + ' after ' + C.iterations[i] + ' iterations: ' + C.termination[i], !C.converged[i]);
    row('identifiable', C.identifiability[i], !C.identifiable[i]);
    if (C.contact_point[i] !== null)
      row('contact point', fmt(C.contact_point[i], 'm') + (C.contact_point_err[i] !== null ? ' \u00b1 ' + fmt(C.contact_point_err[i], 'm') : '') +
          (C.range_samples[i] ? ', ' + C.range_samples[i] + ' samples in the range' : ''));
    row('samples', C.points[i] + ' on the branch, ' + C.points_in_contact[i] + ' in contact, ' + C.excluded_count[i] + ' excluded');
    if (C.pull_off_force[i] !== null) row('pull-off force', fmt(C.pull_off_force[i], 'N'));
    if (C.baseline_slope[i] !== null && C.baseline_slope[i] !== 0) row('baseline slope', fmt(C.baseline_slope[i], 'N/m'));
    C.warnings[i].forEach(function (w) { row('warning', w, true); });
    C.notices[i].forEach(function (n) { row('note', n, false); });
  }

  // The item's values, keyed as the fit-map CSV's columns (plus the report's own: quality ...).
  function valuesOf(i) {
    var out = {index: i};
    Object.keys(C).forEach(function (k) {
      var v = C[k][i];
      out[k] = Array.isArray(v) ? v.slice() : v;
    });
    return out;
  }

  function select(i) {
    if (typeof i !== 'number' || !Number.isInteger(i) || i < 0 || i >= N)
      throw new RangeError('layerjkr.select: curve index ' + i + ' is not in 0 .. ' + (N - 1));
    state.selected = i;
    if (where[i] && where[i].view !== state.view) {
      state.view = where[i].view;
      document.getElementById('view').value = String(state.view);
      drawMap();
    } else {
      moveMarker();
    }
    drawCurve(i);
    drawValues(i);
    return valuesOf(i);
  }

  // Arrow keys: the next pixel with a curve in that direction (on screen) of the current view.
  function step(dx, dyScreen) {
    var v = D.views[state.view];
    if (state.selected < 0 || !where[state.selected] || where[state.selected].view !== state.view) {
      for (var c0 = 0; c0 < v.cells.length; ++c0) if (v.cells[c0] >= 0) return select(v.cells[c0]);
      return null;
    }
    var p = xy(v, where[state.selected].cell);
    var dy = v.kind === 'grid' ? -dyScreen : dyScreen;  // grid maps have y up, index views rows down
    for (var x = p.x + dx, y = p.y + dy; x >= 0 && x < v.nx && y >= 0 && y < v.ny; x += dx, y += dy) {
      var i = v.cells[y * v.nx + x];
      if (i >= 0) return select(i);
    }
    return null;
  }

  document.addEventListener('keydown', function (ev) {
    var t = ev.target, tag = t && t.tagName;
    if (tag === 'SELECT' || tag === 'TEXTAREA' || (tag === 'INPUT' && t.type !== 'checkbox')) return;
    var moves = {ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1]};
    var m = moves[ev.key];
    if (!m) return;
    ev.preventDefault();
    step(m[0], m[1]);
  });

  // ---- controls
  function setup() {
    var viewSel = document.getElementById('view');
    D.views.forEach(function (v, k) {
      var o = document.createElement('option');
      o.value = String(k);
      o.textContent = v.name + ' (' + v.nx + ' x ' + v.ny + ')';
      viewSel.appendChild(o);
    });
    viewSel.addEventListener('change', function () { state.view = Number(viewSel.value); drawMap(); });
    var fieldSel = document.getElementById('field');
    FIELDS.forEach(function (f) {
      var o = document.createElement('option');
      o.value = f.key;
      o.textContent = f.label + (f.unit ? ' [' + f.unit + ']' : '');
      fieldSel.appendChild(o);
    });
    fieldSel.addEventListener('change', function () { state.field = fieldSel.value; drawMap(); });
    var filter = document.getElementById('filter');
    var counts = {};
    C.quality.forEach(function (q) { counts[q] = (counts[q] || 0) + 1; });
    QUALITIES.forEach(function (q) {
      if (!SYMBOL[q]) return;  // 'ok' has no marker
      var label = document.createElement('label'), box = document.createElement('input'), sw = document.createElement('span');
      box.type = 'checkbox';
      box.checked = true;
      box.value = q;
      box.id = 'show-' + q.replace(/ /g, '-');
      box.addEventListener('change', function () { state.show[q] = box.checked; drawMap(); });
      sw.className = 'swatch';
      sw.style.background = COLOUR[q];
      label.appendChild(box);
      label.appendChild(sw);
      label.appendChild(document.createTextNode(q + ' (' + (counts[q] || 0) + ')'));
      filter.appendChild(label);
    });
    var parts = QUALITIES.filter(function (q) { return counts[q]; }).map(function (q) { return counts[q] + ' ' + q; });
    document.getElementById('summary').textContent = N + ' curves: ' + parts.join(', ') + '. Curves shown with at most ' +
        D.display_points + ' samples (plus the ends of excluded spans).';
    mapDiv.on('plotly_click', function (ev) {
      if (!ev || !ev.points || !ev.points.length) return;
      var v = D.views[state.view], p = ev.points[0];
      var x = Math.round(Number(p.x)), y = Math.round(Number(p.y));
      if (x < 0 || x >= v.nx || y < 0 || y >= v.ny) return;
      var i = v.cells[y * v.nx + x];
      if (i >= 0) select(i);
    });
  }

  if (!D.views.length) {  // a batch of no curves
    document.getElementById('summary').textContent = 'No curves.';
    window.layerjkr = {select: select, state: function () { return null; }, pixelPosition: function () { return null; }, data: D};
    return;
  }
  Plotly.newPlot(mapDiv, [], {}, CONFIG);
  setup();
  drawMap();
  // The first curve of the first view, so the page never opens empty.
  var first = D.views.length ? D.views[0].cells.filter(function (i) { return i >= 0; })[0] : undefined;
  if (first !== undefined) select(first);

  window.layerjkr = {
    select: select,
    // What the page shows now: view, field, selected item, which statuses are marked and how
    // many pixels of the current view are drawn (every pixel with a curve: marks never hide one).
    state: function () {
      var v = D.views[state.view], shown = 0;
      v.cells.forEach(function (i) { if (i >= 0 && visible(i)) ++shown; });
      return {view: state.view, field: state.field, selected: state.selected,
              show: QUALITIES.filter(function (q) { return state.show[q]; }), shown: shown};
    },
    // The screen position (page pixels) of item i's pixel in its view, for tests that click.
    pixelPosition: function (i) {
      if (!where[i] || where[i].view !== state.view) return null;
      var p = xy(D.views[state.view], where[i].cell), L = mapDiv._fullLayout, box = mapDiv.getBoundingClientRect();
      return {x: box.left + L.xaxis._offset + L.xaxis.l2p(p.x), y: box.top + L.yaxis._offset + L.yaxis.l2p(p.y)};
    },
    data: D
  };
})();
