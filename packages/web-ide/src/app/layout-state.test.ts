import { describe, it, expect } from 'vitest';
import { parseLayout } from './layout-state.js';

const vs = { cursorState: [{ inSelectionMode: false, selectionStart: { lineNumber: 3, column: 2 }, position: { lineNumber: 3, column: 2 } }], viewState: { scrollTop: 40, scrollLeft: 0 }, contributionsState: {} };

describe('parseLayout (the stored layout is read defensively)', () => {
  it('reads a well-formed layout', () => {
    const l = parseLayout(JSON.stringify({ v: 1, tabs: ['a.contract', 'view:architecture', 'b.contract'], active: 'b.contract', viewStates: { 'a.contract': vs }, sidebarWidth: 300, panelHeight: 250, panel: 'generate', archDocked: true }));
    expect(l).toEqual({ v: 1, tabs: ['a.contract', 'view:architecture', 'b.contract'], active: 'b.contract', viewStates: { 'a.contract': vs }, sidebarWidth: 300, panelHeight: 250, panel: 'generate', archDocked: true });
  });

  it('ignores corrupt or foreign JSON', () => {
    for (const raw of [null, '', '{bad', '[]', 'null', '42', '{"v":2,"tabs":["a"]}', '"text"']) expect(parseLayout(raw)).toBeUndefined();
  });

  it('drops malformed fields one by one and bounds the rest', () => {
    const l = parseLayout(JSON.stringify({
      v: 1, tabs: ['a.contract', 7, '', 'a.contract', 'x'.repeat(2000), 'c.contract'], active: 'gone.contract',
      viewStates: { 'a.contract': 'nope', 'c.contract': vs, 'other.contract': vs }, sidebarWidth: 1e9, panelHeight: 'tall', panel: '"><img>', archDocked: 'yes',
    }))!;
    expect(l.archDocked).toBeUndefined();
    expect(l.tabs).toEqual(['a.contract', 'c.contract']);
    expect(l.active).toBeUndefined();
    expect(Object.keys(l.viewStates)).toEqual(['c.contract']);
    expect(l.sidebarWidth).toBe(600);
    expect(l.panelHeight).toBeUndefined();
    expect(l.panel).toBeUndefined();
  });
});
