/**
 * The `.gitignore` that `contract new` writes (docs/getting-started.md "Keeping a project in
 * git"): what ContrACT Studio writes into a project that is no source. `src-gen/` with its manifest
 * and `src-gen/orphans/` (the only copy of code the generator moved aside) are committed.
 */
export const PROJECT_GITIGNORE = [
    '# contract run\'s logs (the last run, and previous/ runs before it)',
    'logs/',
    '# the generated tree\'s write lock, and the journal of a rename being done (docs/codegen.md)',
    'src-gen/.contract-lock',
    'src-gen/.contract-rename.json',
    '# a make run by hand in src-gen/generated/architecture (contract build works in a private copy)',
    '*.o',
    '',
].join('\n');
