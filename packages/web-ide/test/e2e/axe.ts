import { AxeBuilder } from '@axe-core/playwright';
import type { Page } from 'playwright-core';

export interface AxeSummary {
  screen: string;
  violations: Array<{ id: string; impact: string; nodes: number; help: string; targets: string[] }>;
}

/**
 * An axe-core scan of the page as it is (WCAG 2.x A/AA rules); Monaco's own editor DOM is left out
 * (a third-party widget with its own accessibility mode), unless `editor`: then the editor's text
 * is scanned too — its colours are the IDE's theme (line numbers, keywords, the current line).
 * The report is printed in the test output.
 */
export async function axeScan(page: Page, screen: string, opts: { editor?: boolean } = {}): Promise<AxeSummary> {
  let builder = new AxeBuilder({ page }).withTags(['wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa', 'best-practice']);
  if (!opts.editor) builder = builder.exclude('.monaco-editor').exclude('.monaco-diff-editor');
  const r = await builder.analyze();
  const violations = r.violations.map((v) => ({
    id: v.id, impact: v.impact ?? 'unknown', nodes: v.nodes.length, help: v.help,
    targets: v.nodes.slice(0, 3).map((n) => n.target.join(' ')),
  }));
  const lines = violations.map((v) => `  [${v.impact}] ${v.id} (${v.nodes}×): ${v.help} — e.g. ${v.targets.join(' | ')}`);
  console.log(`axe-core on "${screen}": ${r.passes.length} rules pass, ${violations.length} violation(s)${lines.length ? `\n${lines.join('\n')}` : ''}`);
  return { screen, violations };
}

/** The serious and critical violations of a scan (what the tests forbid). */
export const seriousOf = (s: AxeSummary) => s.violations.filter((v) => v.impact === 'serious' || v.impact === 'critical').map((v) => `${v.id}: ${v.help} (${v.targets.join(' | ')})`);
