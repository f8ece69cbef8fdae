export { startIdeServer, DEFAULT_PORT, type IdeServer, type IdeServerOptions } from './ide-server.js';
export { runServe, parseServeArgs } from './cli.js';
export { WorkspacePaths } from './workspace-paths.js';
export { writeFileAtomic } from './atomic-write.js';
export { PROJECT_TEMPLATES } from './project-templates.js';
