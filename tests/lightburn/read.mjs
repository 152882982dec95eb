// Read LightBurn projects with lbrnts (a reader not written by weave-cut) and print what it
// found as JSON, for tests/lightburn_readback.py:
//
//   node read.mjs FILE.lbrn2 ...        -> [{cutSettings, paths, notes, others, ...}, ...]
//   node read.mjs --svg IN.lbrn2 OUT.svg -> lbrnts's own SVG picture of IN
//
// Every path is reported as lbrnts parsed it: its layer (cutIndex), its vertices with every
// XForm above it applied (mm, y up), and its primitives. lbrnts 0.0.17 marks every path whose
// PrimList lists its lines ("L0 1L1 2") closed, also an open one (LightBurn's own open line,
// tests/export/lightburn_reference/line.lbrn2, is written so); a path closes when its last
// line returns to the first vertex, that is when it has as many lines as vertices, which is
// what "closed" says here and what the SVG picture is drawn with.
import { readFileSync, writeFileSync } from "node:fs";
import {
  CutSetting,
  LightBurnBaseElement,
  LightBurnProject,
  Notes,
  ShapeGroup,
  ShapePath,
  UIPrefs,
  generateLightBurnSvg,
} from "lbrnts";

function parse(path) {
  ShapePath.clearTemplateRegistry(); // lbrnts keeps shared geometry between parses
  const project = LightBurnBaseElement.parse(readFileSync(path, "utf8"));
  if (!(project instanceof LightBurnProject)) {
    throw new Error(`${path}: not a LightBurnProject`);
  }
  return project;
}

function times([a, b, c, d, e, f], [a2, b2, c2, d2, e2, f2]) {
  // the matrix [a c e; b d f] applied after [a2 c2 e2; b2 d2 f2]
  return [a * a2 + c * b2, b * a2 + d * b2, a * c2 + c * d2, b * c2 + d * d2,
          a * e2 + c * f2 + e, b * e2 + d * f2 + f];
}

function closes(path) {
  return path.verts.length > 0 && path.prims.length === path.verts.length;
}

function shapes(children, matrix, out) {
  for (const child of children) {
    const m = times(matrix, child.xform ?? [1, 0, 0, 1, 0, 0]);
    if (child instanceof ShapeGroup) {
      shapes(child.children, m, out);
    } else if (child instanceof ShapePath) {
      const [a, b, c, d, e, f] = m;
      out.paths.push({
        cutIndex: child.cutIndex,
        verts: child.verts.map((v) => [a * v.x + c * v.y + e, b * v.x + d * v.y + f]),
        prims: child.prims.map((p) => p.type),
        lbrntsClosed: child.isClosed,
        closed: closes(child),
      });
    } else if (child.token && child.token.startsWith("Shape.")) {
      out.others[child.token] = (out.others[child.token] ?? 0) + 1;
    }
  }
}

function report(path) {
  const project = parse(path);
  const out = {
    appVersion: project.appVersion,
    formatVersion: project.formatVersion,
    cutSettings: [],
    paths: [],
    others: {},
    notes: null,
    uiPrefs: {},
  };
  for (const child of project.children) {
    if (child instanceof CutSetting) {
      out.cutSettings.push({
        type: child.type, index: child.index, name: child.name, priority: child.priority,
        minPower: child.minPower, maxPower: child.maxPower, speed: child.speed,
        numPasses: child.numPasses,
      });
    } else if (child instanceof Notes) {
      out.notes = { showOnLoad: child.showOnLoad, text: child.text };
    } else if (child instanceof UIPrefs) {
      out.uiPrefs = child.prefs;
    }
  }
  shapes(project.children.filter((c) => !(c instanceof CutSetting)), [1, 0, 0, 1, 0, 0], out);
  return out;
}

function markOpen(children) {
  for (const child of children) {
    if (child instanceof ShapeGroup) markOpen(child.children);
    if (child instanceof ShapePath) child.isClosed = closes(child);
  }
}

const args = process.argv.slice(2);
if (args[0] === "--svg") {
  const project = parse(args[1]);
  markOpen(project.children);
  writeFileSync(args[2], generateLightBurnSvg(project, { defaultStrokeWidth: 0.5 }));
} else {
  process.stdout.write(JSON.stringify(args.map(report)));
}
