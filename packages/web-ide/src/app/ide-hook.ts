/**
 * The page's test hook, `window.__ide`: the IDE's parts, set by main.ts once the IDE is ready
 * (`document.body.dataset.ready`; absent before). The browser tests (test/e2e) reach the parts
 * through it in `page.evaluate`, typed by this one declaration: they import it as a type
 * (`import type {} from '../../src/app/ide-hook.js'`), so a misspelt part or method fails the type
 * check (`npm run typecheck`: tsconfig.test.json) rather than a browser test at run time.
 */
import type { monaco } from '../editor/monaco.js';
import type { Workspace } from '../workspace/workspace.js';
import type { EditorArea } from '../editor/editor-area.js';
import type { LspClient } from '../lsp/lsp-client.js';
import type { ProblemsPanel } from '../panels/problems.js';
import type { BuildPanel } from '../build/build-panel.js';
import type { MonitorController } from '../monitor/monitor-controller.js';
import type { SimulateController } from '../simulate/simulate-controller.js';
import type { CommandRegistry } from './commands.js';
import type { ViewsController } from './views-controller.js';

/** The IDE's parts the page hands to its tests. */
export interface IdeHook {
  workspace: Workspace;
  editors: EditorArea;
  lsp: LspClient;
  problems: ProblemsPanel;
  build: BuildPanel;
  monaco: typeof monaco;
  monitor: MonitorController;
  simulate: SimulateController;
  commands: CommandRegistry;
  views: ViewsController;
}

declare global {
  interface Window {
    /** The IDE's parts for the browser tests, once the IDE is ready (src/app/ide-hook.ts). */
    __ide: IdeHook;
  }
}
