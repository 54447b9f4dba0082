// The script of `pierce report`'s page (report.html): reads the report's data (the JSON in
// #pierce-data, written by apps/pierce/cmd_report.cpp; its fields are described in
// docs/REPORT.md), draws the 3D view with three.js and fills the tables.
//
// Contracts the browser tests rely on (tests/report/):
//  - <html data-ready="1"> once the page is built and the view drawn (data-build-ms: how long that
//    took);
//  - <html data-selected="N"> once finding N is selected and the camera has arrived; a row click
//    and a page address ending in #finding=N take the same path, selectFinding(N) (a click flies
//    the camera there, an address puts it there at once);
//  - #map=thickness|pairs|plain in the address opens that map (with finding=N: #map=pairs&finding=4).
(function () {
  'use strict';

  var started = performance.now();
  var data = JSON.parse(document.getElementById('pierce-data').textContent);
  var root = document.documentElement;

  // ---- small helpers ----

  function el(tag, attrs, children) {
    var e = document.createElement(tag);
    if (attrs) Object.keys(attrs).forEach(function (k) {
      if (k === 'text') e.textContent = attrs[k];
      else if (k === 'className') e.className = attrs[k];
      else e.setAttribute(k, attrs[k]);
    });
    (children || []).forEach(function (c) { e.appendChild(typeof c === 'string' ? document.createTextNode(c) : c); });
    return e;
  }

  // A number as the tables show it: six significant digits, '–' where missing.
  function num(v) {
    if (v === null || v === undefined || (typeof v === 'number' && isNaN(v))) return '\u2013';
    if (typeof v !== 'number') return String(v);
    if (v === 0 || Number.isInteger(v)) return String(v);
    return String(Number(v.toPrecision(6)));
  }
  // A point as the findings tables show it: four significant digits per coordinate.
  function point(p) {
    return p ? '(' + p.map(function (v) { return String(Number(v.toPrecision(4))); }).join(', ') + ')' : '\u2013';
  }
  function count(v) { return v === undefined || v === null ? '\u2013' : Number(v).toLocaleString('en-US'); }

  function table(headers, rows, options) {
    var thead = el('thead', null, [el('tr', null, headers.map(function (h) {
      return el('th', { text: h });
    }))]);
    var tbody = el('tbody');
    rows.forEach(function (r) { tbody.appendChild(r); });
    var box = el('div', { className: 'table-box' }, [el('table', options || null, [thead, tbody])]);
    return box;
  }
  function row(cells, attrs) {
    return el('tr', attrs, cells.map(function (c) {
      if (c instanceof Node) return c;
      return el('td', { text: c });
    }));
  }
  function cell(text, className) { return el('td', { text: text, className: className || '' }); }

  function decode(base64, Type) {
    var bin = atob(base64 || '');
    var bytes = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
    return new Type(bytes.buffer);
  }

  function solidName(id) {
    var s = data.solid_names[id];
    return s ? s : '#' + id;
  }

  // ---- colours ----

  // Thickness ramp from red (thin) through yellow and green to blue (thick).
  var RAMP = [[0.84, 0.15, 0.11], [0.99, 0.55, 0.23], [1.0, 0.88, 0.35], [0.55, 0.80, 0.40], [0.20, 0.60, 0.75],
              [0.19, 0.30, 0.70]];
  function ramp(t) {
    t = Math.min(1, Math.max(0, t)) * (RAMP.length - 1);
    var i = Math.min(RAMP.length - 2, Math.floor(t)), f = t - i, a = RAMP[i], b = RAMP[i + 1];
    return [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f];
  }
  function css(c) { return 'rgb(' + c.map(function (x) { return Math.round(x * 255); }).join(',') + ')'; }
  var GREY = [0.62, 0.62, 0.64], THIN = [0.85, 0.0, 0.75], PLAIN = [0.80, 0.81, 0.83];
  var PAIR_COLOURS = { free: [0.80, 0.81, 0.83], clearance: [0.15, 0.65, 0.25], contact: [1.0, 0.55, 0.0],
                       clash: [0.90, 0.05, 0.05] };
  var PAIR_CATEGORY = ['free', 'clearance', 'contact', 'clash'];
  var SOLID_TINTS = [[0.78, 0.80, 0.86], [0.86, 0.80, 0.72], [0.74, 0.84, 0.76], [0.86, 0.76, 0.82],
                     [0.76, 0.82, 0.88], [0.88, 0.86, 0.72]];
  var MARKER_COLOURS = { thin: 0xd400bf, thick: 0x1f3fbf, clash: 0xe00000, contact: 0xff8c00, clearance: 0x14a028 };

  var thresholdInput = document.getElementById('threshold');
  var threshold = data.options.min_thickness > 0 ? data.options.min_thickness : 0;
  thresholdInput.value = threshold > 0 ? String(threshold) : '';

  // The thickness range the ramp spans: all measured values over the sampled solids.
  var range = data.thickness_range || [0, 1];
  if (!(range[1] > range[0])) range = [range[0], range[0] + 1];

  // ---- the 3D view ----

  var view = document.getElementById('view');
  var legend = document.getElementById('legend');
  var three = null;  // {renderer, scene, camera, controls, mesh, markers, ...} once WebGL runs
  var mesh = data.mesh;
  var currentMap = 'thickness';

  function buildView() {
    var renderer;
    try {
      renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    } catch (e) {
      document.getElementById('no-webgl').hidden = false;
      return null;
    }
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setClearColor(0xffffff, 1);
    view.appendChild(renderer.domElement);

    var q = decode(mesh.positions, Uint16Array), tris = decode(mesh.triangles, Uint32Array);
    var triSolid = decode(mesh.triangle_solid, Uint16Array);
    var nTri = tris.length / 3;
    // Triangles unshared (three vertices each): faces keep their own colour and flat normals.
    var pos = new Float32Array(nTri * 9);
    for (var t = 0; t < nTri; t++)
      for (var k = 0; k < 3; k++) {
        var v = tris[3 * t + k];
        for (var a = 0; a < 3; a++) pos[9 * t + 3 * k + a] = mesh.origin[a] + q[3 * v + a] * mesh.scale[a];
      }
    var geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    geometry.computeVertexNormals();
    var colours = new Float32Array(nTri * 9);
    geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    var material = new THREE.MeshLambertMaterial({ vertexColors: THREE.VertexColors, side: THREE.DoubleSide });
    var surface = new THREE.Mesh(geometry, material);

    var scene = new THREE.Scene();
    scene.add(surface);
    scene.add(new THREE.AmbientLight(0xffffff, 0.5));
    var camera = new THREE.PerspectiveCamera(35, 1, 1e-3, 1e3);
    var light = new THREE.DirectionalLight(0xffffff, 0.6);
    light.position.set(0.3, 0.5, 1);
    camera.add(light);
    scene.add(camera);

    var lo = data.bounds[0], hi = data.bounds[1];
    var centre = new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
    var diag = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
    camera.near = diag * 1e-3;
    camera.far = diag * 100;
    camera.updateProjectionMatrix();

    var controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.screenSpacePanning = true;

    var vertexValues = mesh.thickness && mesh.thickness.at === 'vertex' ? decode(mesh.thickness.values, Float32Array) : null;
    var faceValues = mesh.thickness && mesh.thickness.at === 'face' ? decode(mesh.thickness.values, Float32Array) : null;
    var pairCategory = mesh.pairs ? decode(mesh.pairs.category, Uint8Array) : null;
    var pairGap = mesh.pairs ? decode(mesh.pairs.gap, Float32Array) : null;

    three = { renderer: renderer, scene: scene, camera: camera, controls: controls, surface: surface,
              colours: colours, tris: tris, triSolid: triSolid, nTri: nTri, vertexValues: vertexValues,
              faceValues: faceValues, pairCategory: pairCategory, pairGap: pairGap, centre: centre, diag: diag,
              markers: [], selected: null, segment: null, pending: false };
    buildMarkers();
    resetView();
    controls.addEventListener('change', requestRender);
    window.addEventListener('resize', function () { resize(); requestRender(); });
    resize();
    return three;
  }

  function thicknessColour(v) {
    if (!(v === v)) return GREY;  // NaN: no thickness
    if (threshold > 0 && v < threshold) return THIN;
    return ramp((v - range[0]) / (range[1] - range[0]));
  }

  function colourMesh() {
    var c = three.colours, tris = three.tris;
    for (var t = 0; t < three.nTri; t++) {
      for (var k = 0; k < 3; k++) {
        var col;
        if (currentMap === 'thickness') {
          if (three.vertexValues) col = thicknessColour(three.vertexValues[tris[3 * t + k]]);
          else if (three.faceValues) col = thicknessColour(three.faceValues[t]);
          else col = GREY;
        } else if (currentMap === 'pairs' && three.pairCategory) {
          var cat = PAIR_CATEGORY[three.pairCategory[t]] || 'free';
          col = PAIR_COLOURS[cat];
          if (cat === 'clearance' && data.options.clearance > 0) col = clearanceColour(three.pairGap[t] / data.options.clearance);
        } else {
          col = SOLID_TINTS[three.triSolid[t] % SOLID_TINTS.length];
        }
        c[9 * t + 3 * k] = col[0];
        c[9 * t + 3 * k + 1] = col[1];
        c[9 * t + 3 * k + 2] = col[2];
      }
    }
    three.surface.geometry.attributes.color.needsUpdate = true;
    drawLegend();
    requestRender();
  }

  // Clearance triangles: yellow where they touch (gap 0) to green at the clearance asked for.
  function clearanceColour(f) {
    f = Math.min(1, Math.max(0, f));
    return [0.95 - 0.8 * f, 0.85 - 0.2 * f, 0.2 + 0.05 * f];
  }

  function drawLegend() {
    legend.textContent = '';
    if (currentMap === 'thickness') {
      legend.appendChild(el('div', { text: 'Thickness' }));
      var stops = [];
      for (var i = 0; i <= 10; i++) stops.push(css(ramp(1 - i / 10)) + ' ' + (i * 10) + '%');
      var bar = el('span', { className: 'bar' });
      bar.style.background = 'linear-gradient(' + stops.join(',') + ')';
      var ticks = el('span', { className: 'ticks' });
      var thresholdAt = (range[1] - threshold) / (range[1] - range[0]);
      for (var j = 0; j <= 4; j++) {
        if (threshold > 0 && Math.abs(thresholdAt - j / 4) < 0.08) continue;  // the threshold's label is there
        var v = range[1] - (range[1] - range[0]) * j / 4;
        var s = el('span', { text: num(v) });
        s.style.top = (j * 25) + '%';
        ticks.appendChild(s);
      }
      if (threshold > 0 && threshold > range[0] && threshold < range[1]) {
        var th = el('span', { className: 'threshold', text: '\u2190 ' + num(threshold) + ' thin' });
        th.style.top = (100 * thresholdAt) + '%';
        ticks.appendChild(th);
      }
      legend.appendChild(el('div', null, [bar, ticks]));
      if (threshold > 0) legend.appendChild(swatch(THIN, 'thin (< ' + num(threshold) + ')'));
      legend.appendChild(swatch(GREY, 'no thickness'));
    } else if (currentMap === 'pairs') {
      legend.appendChild(el('div', { text: 'Between solids' }));
      legend.appendChild(swatch(PAIR_COLOURS.clash, 'clash'));
      legend.appendChild(swatch(PAIR_COLOURS.contact, 'contact'));
      if (data.options.clearance > 0) {
        var gap = swatch(PAIR_COLOURS.clearance, 'gap 0 \u2013 ' + num(data.options.clearance));
        gap.firstChild.style.background = 'linear-gradient(90deg,' + css(clearanceColour(0)) + ',' + css(clearanceColour(1)) + ')';
        legend.appendChild(gap);
      }
      legend.appendChild(swatch(PAIR_COLOURS.free, 'free'));
    } else {
      legend.appendChild(el('div', { text: 'Solids' }));
      data.solid_names.forEach(function (n, id) {
        if (id < 12) legend.appendChild(swatch(SOLID_TINTS[id % SOLID_TINTS.length], solidName(id)));
      });
    }
  }
  function swatch(colour, label) {
    var s = el('span', { className: 'swatch' });
    s.style.background = css(colour);
    return el('div', null, [s, label]);
  }

  function buildMarkers() {
    var radius = three.diag * 0.01;
    var geometry = new THREE.SphereBufferGeometry(1, 16, 12);
    data.findings.forEach(function (f) {
      var material = new THREE.MeshBasicMaterial({ color: MARKER_COLOURS[f.kind] || 0x000000, depthTest: false,
                                                   transparent: true, opacity: 0.85 });
      var m = new THREE.Mesh(geometry, material);
      var p = f.point;
      m.position.set(p[0], p[1], p[2]);
      m.scale.setScalar(radius);
      m.renderOrder = 10;
      m.userData = { finding: f.n, colour: material.color.getHex(), radius: radius };
      three.scene.add(m);
      three.markers.push(m);
    });
  }

  function resize() {
    var w = view.clientWidth, h = view.clientHeight;
    three.renderer.setSize(w, h, false);
    three.camera.aspect = w / Math.max(1, h);
    three.camera.updateProjectionMatrix();
  }

  function render() {
    three.renderer.render(three.scene, three.camera);
  }
  function requestRender() {
    if (!three || three.pending) return;
    three.pending = true;
    requestAnimationFrame(function () { three.pending = false; render(); });
  }

  function resetView() {
    var dir = new THREE.Vector3(0.9, -1.2, 1.5).normalize();  // from above: pockets show their floors
    three.controls.target.copy(three.centre);
    three.camera.position.copy(three.centre).addScaledVector(dir, three.diag * 1.6);
    three.camera.up.set(0, 0, 1);
    three.controls.update();
    requestRender();
  }

  // Moves the camera to look at `target` from `distance`, from the side `side` points to (a unit
  // vector, or null: the current viewing direction), over `ms` milliseconds; calls done() when there.
  function flyTo(target, distance, side, ms, done) {
    var camera = three.camera, controls = three.controls;
    var fromPos = camera.position.clone(), fromTarget = controls.target.clone();
    var dir = fromPos.clone().sub(fromTarget).normalize();
    // From the finding's side, tilted a little towards the current view so the scene keeps some
    // depth (little: more would look at a pocket's floor through its wall).
    if (side) dir = side.clone().addScaledVector(dir, 0.1).normalize();
    var toPos = target.clone().addScaledVector(dir, distance);
    var start = performance.now();
    function step() {
      var s = ms > 0 ? Math.min(1, (performance.now() - start) / ms) : 1;
      var e = s * s * (3 - 2 * s);
      camera.position.lerpVectors(fromPos, toPos, e);
      controls.target.lerpVectors(fromTarget, target, e);
      controls.update();
      render();
      if (s < 1) requestAnimationFrame(step);
      else done();
    }
    step();
  }

  // ---- findings ----

  var rowsByFinding = {};

  // Selects finding n: marks its row and marker and moves the camera to it, flying over 0.7 s
  // when `fly` (a click), at once otherwise (an address naming it, as the page opens).
  function selectFinding(n, fly) {
    var f = null;
    data.findings.forEach(function (x) { if (x.n === n) f = x; });
    if (!f) return;
    Object.keys(rowsByFinding).forEach(function (k) { rowsByFinding[k].classList.remove('selected'); });
    var r = rowsByFinding[n];
    if (r) {
      r.classList.add('selected');
      var box = r.closest('.table-box');
      if (box) box.scrollTop = r.offsetTop - box.clientHeight / 2;
    }
    try {
      history.replaceState(null, '', '#' + (currentMap !== 'thickness' ? 'map=' + currentMap + '&' : '') + 'finding=' + n);
    } catch (e) { /* file: URLs in some browsers */ }
    if (!three) { root.setAttribute('data-selected', String(n)); return; }
    three.markers.forEach(function (m) {
      var on = m.userData.finding === n;
      m.material.color.setHex(on ? 0xffe000 : m.userData.colour);
      m.scale.setScalar(m.userData.radius * (on ? 1.8 : 1));
    });
    if (three.segment) { three.scene.remove(three.segment); three.segment = null; }
    var p = new THREE.Vector3(f.point[0], f.point[1], f.point[2]);
    var target = p.clone(), span = 0, side = null;
    if (f.point_b) {
      var b = new THREE.Vector3(f.point_b[0], f.point_b[1], f.point_b[2]);
      span = p.distanceTo(b);
      // A wall is seen from outside its sampled face: its ray ran inward, from point to point_b.
      if ((f.kind === 'thin' || f.kind === 'thick') && span > 0) side = p.clone().sub(b).normalize();
      target.add(b).multiplyScalar(0.5);
      var g = new THREE.BufferGeometry().setFromPoints([p, b]);
      three.segment = new THREE.Line(g, new THREE.LineBasicMaterial({ color: 0x000000, depthTest: false }));
      three.segment.renderOrder = 11;
      three.scene.add(three.segment);
    }
    var distance = Math.max(span * 8, three.diag * 0.45);
    flyTo(target, distance, side, fly ? 700 : 0, function () { root.setAttribute('data-selected', String(n)); });
  }

  function findingRow(f, cells) {
    var r = row([cell(String(f.n))].concat(cells), { className: 'finding', 'data-finding': String(f.n) });
    r.addEventListener('click', function () { selectFinding(f.n, true); });
    rowsByFinding[f.n] = r;
    return r;
  }

  function buildFindings() {
    var box = document.getElementById('findings-tables');
    var thin = data.findings.filter(function (f) { return f.kind === 'thin'; });
    var thick = data.findings.filter(function (f) { return f.kind === 'thick'; });
    var pairs = data.findings.filter(function (f) { return f.kind === 'clash' || f.kind === 'contact' || f.kind === 'clearance'; });
    var o = data.options;

    box.appendChild(el('h3', { text: o.min_thickness > 0 ? 'Thin walls (thickness < ' + num(o.min_thickness) + '): ' + thin.length
                                                        : 'Thin walls: no threshold given (--min)' }));
    if (thin.length) box.appendChild(table(['#', 'solid', 'min thickness', 'area (both sides)', 'samples', 'at'],
      thin.map(function (f) {
        return findingRow(f, [cell(solidName(f.solid), 'text'), cell(num(f.thickness)), cell(num(f.area)), cell(count(f.samples)),
                              cell(point(f.point))]);
      }), { id: 'thin-table' }));

    if (o.max_thickness !== null) {
      box.appendChild(el('h3', { text: 'Thick walls (thickness > ' + num(o.max_thickness) + '): ' + thick.length }));
      if (thick.length) box.appendChild(table(['#', 'solid', 'max thickness', 'area (both sides)', 'samples', 'at'],
        thick.map(function (f) {
          return findingRow(f, [cell(solidName(f.solid), 'text'), cell(num(f.thickness)), cell(num(f.area)), cell(count(f.samples)),
                                cell(point(f.point))]);
        }), { id: 'thick-table' }));
    }

    if (data.solid_names.length > 1) {
      var counts = { clash: 0, contact: 0, clearance: 0 };
      pairs.forEach(function (f) { counts[f.kind] += 1; });
      box.appendChild(el('h3', { text: 'Solid pairs' + (o.clearance > 0 ? ' within ' + num(o.clearance) : '') + ': ' +
        counts.clash + ' clash, ' + counts.contact + ' contact, ' + counts.clearance + ' clearance' }));
      if (pairs.length) box.appendChild(table(['#', 'kind', 'solid A', 'solid B', 'gap', 'depth', 'volume', 'at'],
        pairs.map(function (f) {
          return findingRow(f, [cell(f.kind, 'text kind-' + f.kind), cell(solidName(f.solid), 'text'), cell(solidName(f.solid_b), 'text'),
                                cell(num(f.gap)), cell(num(f.depth)), cell(num(f.volume)), cell(point(f.point))]);
        }), { id: 'pairs-table' }));
    } else {
      box.appendChild(el('p', { className: 'note', text: 'One solid: no contact, clash or clearance to report.' }));
    }
  }

  // ---- per solid: summary and histogram ----

  function histogram(s) {
    var W = 320, H = 130, padL = 34, padB = 26, padT = 6;
    var ns = 'http://www.w3.org/2000/svg';
    var svg = document.createElementNS(ns, 'svg');
    svg.setAttribute('width', W);
    svg.setAttribute('height', H);
    svg.setAttribute('role', 'img');
    var edges = s.histogram.edges, counts = s.histogram.counts;
    var lo = edges[0], hi = edges[edges.length - 1], top = Math.max.apply(null, counts.concat([1]));
    function x(v) { return padL + (W - padL - 6) * (hi > lo ? (v - lo) / (hi - lo) : 0); }
    function y(c) { return padT + (H - padT - padB) * (1 - c / top); }
    function add(tag, attrs) {
      var e = document.createElementNS(ns, tag);
      Object.keys(attrs).forEach(function (k) { e.setAttribute(k, attrs[k]); });
      svg.appendChild(e);
      return e;
    }
    counts.forEach(function (c, i) {
      var mid = (edges[i] + edges[i + 1]) / 2;
      add('rect', { x: x(edges[i]) + 0.5, y: y(c), width: Math.max(1, x(edges[i + 1]) - x(edges[i]) - 1),
                    height: y(0) - y(c), fill: css(thicknessColour(mid)) });
    });
    add('line', { x1: padL, y1: y(0), x2: W - 6, y2: y(0), stroke: '#555' });
    add('line', { x1: padL, y1: padT, x2: padL, y2: y(0), stroke: '#555' });
    [lo, (lo + hi) / 2, hi].forEach(function (v, i) {
      add('text', { x: x(v), y: H - 8, 'font-size': 10, 'text-anchor': ['start', 'middle', 'end'][i] }).textContent = num(v);
    });
    add('text', { x: padL - 4, y: padT + 8, 'font-size': 10, 'text-anchor': 'end' }).textContent = num(top);
    add('text', { x: padL - 4, y: y(0), 'font-size': 10, 'text-anchor': 'end' }).textContent = '0';
    if (threshold > lo && threshold < hi)
      add('line', { x1: x(threshold), y1: padT, x2: x(threshold), y2: y(0), stroke: '#c00', 'stroke-dasharray': '3,2' });
    return svg;
  }

  function buildSolids() {
    var box = document.getElementById('solid-summary');
    var pcts = data.percentiles;
    box.appendChild(table(['solid', 'samples', 'measured', 'min'].concat(pcts.map(function (p) { return 'p' + p; }))
      .concat(['max', 'mean', 'thin', 'thick']), data.solids.map(function (s) {
      var t = s.thickness || {};
      return row([cell(solidName(s.id), 'text'), cell(count(s.elements)), cell(count(s.valid)), cell(num(t.min))]
        .concat(pcts.map(function (p) { return cell(num(t.percentiles ? t.percentiles['p' + p] : null)); }))
        .concat([cell(num(t.max)), cell(num(t.mean)), cell(count(s.thin)), cell(count(s.thick))]));
    }), { id: 'solid-table' }));
    data.solids.forEach(function (s) {
      if (!s.thickness) return;
      box.appendChild(el('div', { className: 'solid-card' }, [
        el('div', { text: solidName(s.id) + ': histogram of ' + count(s.valid) + ' thicknesses' }), histogram(s)]));
    });
  }

  // ---- model checks ----

  function buildChecks() {
    var box = document.getElementById('check-tables');
    var cad = data.solids.some(function (s) { return s.checks.tessellation; });
    var headers = ['solid', 'source', 'triangles', 'closed', 'boundary edges', 'non-manifold edges',
                   'inconsistently oriented edges', 'degenerate', 'duplicated'];
    if (cad) headers = headers.concat(['folded (CAD)', 'slivers (CAD)', 'faces remeshed (CAD)']);
    box.appendChild(table(headers, data.solids.map(function (s) {
      var c = s.checks;
      var cells = [cell(solidName(s.id), 'text'), cell(c.source, 'text'), cell(count(c.triangles)),
                   cell(c.closed ? 'closed' : 'OPEN', c.closed ? '' : 'bad'), cell(count(c.boundary_edges), c.boundary_edges ? 'bad' : ''),
                   cell(count(c.non_manifold_edges), c.non_manifold_edges ? 'bad' : ''),
                   cell(count(c.inconsistent_edges), c.inconsistent_edges ? 'bad' : ''), cell(count(c.degenerate_triangles)),
                   cell(count(c.duplicate_triangles))];
      if (cad) {
        var tc = c.tessellation || {};
        cells = cells.concat([cell(count(tc.folded_triangles), tc.folded_triangles ? 'bad' : ''), cell(count(tc.sliver_triangles)),
                              cell(count(tc.faces_remeshed))]);
      }
      return row(cells);
    }), { id: 'checks-table' }));

    box.appendChild(el('h3', { text: 'Samples without a thickness' }));
    box.appendChild(table(['solid', 'samples', 'no exit', 'no normal', 'tessellation artefact'], data.solids.map(function (s) {
      return row([cell(solidName(s.id), 'text'), cell(count(s.elements)), cell(count(s.no_exit), s.no_exit ? 'bad' : ''),
                  cell(count(s.no_normal)), cell(count(s.tessellation))]);
    }), { id: 'excluded-table' }));
    box.appendChild(el('p', { className: 'note', text:
      'no exit: the ray along the inward normal did not leave the solid (an open mesh, or beyond --max-distance). ' +
      'no normal: a degenerate face or vertex. tessellation artefact (CAD): the sample starts on, or its ray meets, ' +
      'a triangle folded against the B-rep, or finds no exit in a closed solid; left out of every statistic.' }));
    if (data.warnings.length) {
      box.appendChild(el('h3', { text: 'Loader warnings' }));
      box.appendChild(el('ul', null, data.warnings.map(function (w) { return el('li', { text: w }); })));
    }
  }

  // ---- exactness ----

  function buildExactness() {
    var box = document.getElementById('exactness-body');
    var x = data.exactness;
    if (x.skipped) {
      box.appendChild(el('p', { text: 'Not measured: the epsilon baseline cannot trace this model (' + x.skipped + ').' }));
      return;
    }
    if (!x.rays) {
      box.appendChild(el('p', { text: 'No thickness ray to compare (no sample with a normal).' }));
      return;
    }
    box.appendChild(el('p', { text: 'The first ' + count(x.rays) + ' thickness rays (every ' + count(x.stride) +
      '-th sample, up to a budget of ' + count(x.budget) + '), traced on the mesh on one thread with the exact kernel and ' +
      'with the inexact epsilon baseline (Embree\u2019s closest hit, relaunched ' + num(x.epsilon) +
      ' beyond each hit), each finding where its ray leaves its solid.' }));
    box.appendChild(table(['kernel', 'exact', 'rays', 'time (ms)', 'per ray (\u00b5s)', 'samples wrong'], [
      row([cell(x.exact_kernel, 'text'), cell('yes'), cell(count(x.rays)), cell(num(x.exact_ms)),
           cell(num(1000 * x.exact_ms / x.rays)), cell('0 (the reference)')]),
      row([cell('epsilon', 'text'), cell('no'), cell(count(x.rays)), cell(num(x.epsilon_ms)),
           cell(num(1000 * x.epsilon_ms / x.rays)), cell(count(x.wrong), x.wrong ? 'bad' : '')])
    ], { id: 'exactness-table' }));
    var words = [];
    if (x.wrong === 0) words.push('The baseline agrees with the exact kernel on every sample traced here.');
    else {
      words.push('The baseline gets ' + count(x.wrong) + ' of ' + count(x.rays) + ' samples (' +
        num(100 * x.wrong / x.rays) + ' %) wrong by more than ' + num(x.tolerance) + ':');
      if (x.missed) words.push(count(x.missed) + ' find no exit where there is one;');
      if (x.spurious) words.push(count(x.spurious) + ' find an exit where there is none;');
      if (x.off) words.push(count(x.off) + ' find a different exit, off by up to ' + num(x.max_error) + ' (median ' +
        num(x.median_error) + ', up to ' + num(100 * x.max_relative_error) + ' % of the thickness).');
    }
    words.push('Exactness cost ' + num(x.exact_ms - x.epsilon_ms) + ' ms on these rays (' +
      num(x.epsilon_ms > 0 ? x.exact_ms / x.epsilon_ms : NaN) + ' times the baseline\u2019s time).');
    box.appendChild(el('p', { text: words.join(' ') }));
  }

  // ---- provenance ----

  function buildProvenance() {
    var p = data.provenance, box = document.getElementById('provenance-body');
    var facts = [['command', p.command], ['date (UTC)', p.date], ['Pierce', p.pierce_version]];
    Object.keys(p.dependencies).forEach(function (k) { facts.push([k, p.dependencies[k]]); });
    p.inputs.forEach(function (f) { facts.push(['input', f.path + ' (' + count(f.bytes) + ' bytes)']); });
    var o = data.options;
    facts.push(['thickness', o.method + ' method, per ' + o.per + ', kernel ' + o.kernel]);
    box.appendChild(el('dl', { className: 'facts' }, [].concat.apply([], facts.map(function (f) {
      return [el('dt', { text: f[0] }), el('dd', { text: String(f[1]) })];
    }))));
  }

  function buildHeadline() {
    var thin = data.findings.filter(function (f) { return f.kind === 'thin'; }).length;
    var clash = data.findings.filter(function (f) { return f.kind === 'clash'; }).length;
    var tri = data.mesh.triangles_model;
    var words = [data.solid_names.length + (data.solid_names.length === 1 ? ' solid, ' : ' solids, ') + count(tri) +
                 ' triangles'];
    if (data.options.min_thickness > 0) words.push(thin + ' thin wall' + (thin === 1 ? '' : 's'));
    if (data.solid_names.length > 1) words.push(clash + ' clash' + (clash === 1 ? '' : 'es'));
    if (data.thickness_range) words.push('thickness ' + num(data.thickness_range[0]) + ' to ' + num(data.thickness_range[1]));
    document.getElementById('headline').textContent = words.join(' \u00b7 ');
    var m = data.mesh;
    document.getElementById('display-note').textContent = m.triangles_shown < m.triangles_model
      ? 'The view shows ' + count(m.triangles_shown) + ' of the model\u2019s ' + count(m.triangles_model) +
        ' triangles (vertices clustered on a grid of cell ' + num(m.cell) + ', for display only: every table holds the full results).'
      : 'The view shows all ' + count(m.triangles_model) + ' triangles. Drag to turn, right-drag to pan, wheel to zoom.';
  }

  // ---- wiring ----

  buildHeadline();
  buildFindings();
  buildSolids();
  buildChecks();
  buildExactness();
  buildProvenance();
  if (!data.mesh.pairs) document.querySelector('input[value="pairs"]').disabled = true;

  var wantedMap = /(?:^#|&)map=(thickness|pairs|plain)\b/.exec(location.hash);
  if (wantedMap && !(wantedMap[1] === 'pairs' && !data.mesh.pairs)) {
    currentMap = wantedMap[1];
    document.querySelector('input[name="map"][value="' + currentMap + '"]').checked = true;
  }
  if (buildView()) {
    colourMesh();
    Array.prototype.forEach.call(document.querySelectorAll('input[name="map"]'), function (r) {
      r.addEventListener('change', function () { currentMap = r.value; colourMesh(); });
    });
    thresholdInput.addEventListener('input', function () {
      var v = parseFloat(thresholdInput.value);
      threshold = v > 0 ? v : 0;
      colourMesh();
    });
    document.getElementById('show-markers').addEventListener('change', function (e) {
      three.markers.forEach(function (m) { m.visible = e.target.checked; });
      requestRender();
    });
    document.getElementById('reset-view').addEventListener('click', resetView);
    render();
    // Where the view is on the page, in CSS pixels: the browser tests look at those pixels.
    var box = view.getBoundingClientRect();
    root.setAttribute('data-view-rect', [box.left, box.top, box.width, box.height].map(Math.round).join(','));
  }
  // How long reading the data, building the view and the tables and the first drawing took.
  root.setAttribute('data-build-ms', String(Math.round(performance.now() - started)));
  root.setAttribute('data-ready', '1');

  var wanted = /(?:^#|&)finding=(\d+)/.exec(location.hash);
  if (wanted) selectFinding(parseInt(wanted[1], 10), false);
})();
