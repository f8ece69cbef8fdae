/**
 * Which Cactal names the generated C cannot take (docs/language-reference.md, "Reserved names").
 * The generator uses Cactal names as they are, so that user code in the protected regions reads
 * the report's variable names; instead, `check` refuses a name that would collide, depending on
 * what the name becomes in C (its role):
 * - datatype: a typedef and a struct tag in every file that includes `common/Shared<T>.h`;
 * - function: a static inline function in the files that include `common/SharedFunction<f>.h`;
 * - module-variable: a global variable of `modules/<M>_mod/module.c` (module ports and parameters);
 * - member: a struct member or a C parameter (fields, schema and supervision-function parameters,
 *   locals): only macros and keywords can break those;
 * - argument: a parameter of a function prototype, which must not hide a datatype of the prototype;
 * - constant: a macro of `common/constants.h`, which every module.c includes after its other headers:
 *   it replaces the name everywhere after it (the request loop, the protected regions, headers the
 *   regions include), so it may be no name of the generated C and no other name of the project's C
 *   (datatype, function, field, argument, module port or parameter, enumeration member's C name).
 * Module, supervisor, schema, rule, supervision-function and supervisor-port names only appear in
 * strings and inside longer generated names, which the generator keeps apart (table-builder.ts).
 */
import { HEADER_DECLARATIONS, HEADER_MACROS, HEADER_TAGS, RUNTIME_LIBRARY_SYMBOLS } from './header-names.js';
import {
    MODULE_GLOBALS, MODULE_LOCALS, MODULE_SOURCE_WORDS, RUNTIME_PREFIXES, SHARED_GUARD, SUPERVISOR_DERIVED, TOOL_AND_VOCABULARY_NAMES,
    TYPE_FUNCTION_PREFIXES, TYPE_HEADER_LOCALS
} from './generated-code-names.js';

export type CNameRole = 'datatype' | 'function' | 'module-variable' | 'member' | 'argument' | 'constant';

/** The project's names that become file-scope C names of their own. */
export interface ProjectCNames {
    readonly datatypes: ReadonlySet<string>;
    /** Named constants: macros of `common/constants.h` in every module.c. */
    readonly constants?: ReadonlySet<string>;
    /** Function prototypes (a constant of that name would replace the function's name). */
    readonly functions?: ReadonlySet<string>;
    /** Enumeration constants (`<Enum>_<member>`) -> the members that become them (`member AUTO of enumeration Mode`). */
    readonly enumConstants?: ReadonlyMap<string, readonly string[]>;
    /** Module ports and parameters (globals of their module.c), for the enumeration members' check. */
    readonly moduleVariables?: ReadonlySet<string>;
}

const macros = new Set(HEADER_MACROS);
const declarations = new Set(HEADER_DECLARATIONS);
const tags = new Set(HEADER_TAGS);
const librarySymbols = new Set(RUNTIME_LIBRARY_SYMBOLS);
const moduleGlobals = new Set(MODULE_GLOBALS);
const moduleLocals = new Set(MODULE_LOCALS);
const typeHeaderLocals = new Set(TYPE_HEADER_LOCALS);
const toolNames = new Set(TOOL_AND_VOCABULARY_NAMES);
const moduleSourceWords = new Set(MODULE_SOURCE_WORDS);
const typeFunction = new RegExp(`^(?:${TYPE_FUNCTION_PREFIXES.join('|')})_(\\w+)$`);

/** Why `name` cannot take `role` in the generated C, or undefined when it can. */
export function cNameConflict(name: string, role: CNameRole, project: ProjectCNames): string | undefined {
    if (macros.has(name)) return 'it is a macro of the C library or runtime headers that the generated C includes';
    if (role !== 'constant' && role !== 'datatype' && project.constants?.has(name)) {
        return 'a named constant has that name, and constants are macros in the generated C (common/constants.h, included by every module.c)';
    }
    if (role === 'member') return undefined;
    const member = role !== 'argument' && role !== 'constant' ? project.enumConstants?.get(name)?.[0] : undefined;
    if (member) return `${member} becomes the C enumeration constant ${name}, a file-scope name`;
    if (role === 'argument') {
        return project.datatypes.has(name) ? 'it names a datatype, which the generated prototype may use for another argument' : undefined;
    }
    if (declarations.has(name)) return 'the C library, POSIX or runtime headers that the generated C includes already declare it';
    if (librarySymbols.has(name)) return 'the runtime library defines or calls a global of that name, which a generated global would replace';
    const fileScope = role === 'datatype' || role === 'constant';
    if (fileScope && tags.has(name)) return 'it is already a struct tag of the C library headers that the generated C includes';
    const prefix = RUNTIME_PREFIXES.find((p) => name.startsWith(p));
    if (prefix) return `names starting with '${prefix}' belong to the runtime and the generated tables`;
    if (SUPERVISOR_DERIVED.test(name) || SHARED_GUARD.test(name)) return 'it has the form of a name the generated C builds (a supervisor\'s table or a header guard)';
    const typeFn = typeFunction.exec(name);
    if (typeFn && project.datatypes.has(typeFn[1]!)) return `it is the name of a function generated for datatype ${typeFn[1]} (common/Shared${typeFn[1]}.h)`;
    if (role !== 'datatype' && role !== 'constant' && project.datatypes.has(name)) return 'it names a datatype, a type name in the generated C';
    if (role === 'constant' && project.functions?.has(name)) return 'it names a function, whose name a constant (a macro in the generated C) would replace';
    if ((role === 'module-variable' || fileScope) && moduleGlobals.has(name)) return 'every generated module.c declares a global of that name';
    if (role === 'module-variable' && moduleLocals.has(name)) return 'the generated module.c functions declare a variable of that name, which would hide the port where the generated code and the regions read it';
    if (role === 'datatype' && moduleLocals.has(name)) return 'the generated module.c functions declare a variable of that name, which would hide the type where the generated code takes its size (sizeof)';
    if (role === 'constant' && (moduleLocals.has(name) || moduleSourceWords.has(name))) return 'the generated module.c uses that name after the constants, which are macros there';
    if (role === 'constant' && typeHeaderLocals.has(name)) return 'the functions generated for every datatype declare a variable of that name, which a constant (a macro) would replace in the headers included after it';
    if (role === 'datatype' && typeHeaderLocals.has(name)) return 'the functions generated for every datatype declare a variable of that name, which would hide the type';
    if ((fileScope || role === 'function') && toolNames.has(name)) return 'the generated control tools or vocabulary tables declare it';
    return undefined;
}

/** The C enumeration constants (`<Enum>_<member>`) of `enums` -> the members that become them (`member AUTO of enumeration Mode`). */
export function enumConstantsOf(enums: Iterable<{ name?: string; members?: ReadonlyArray<{ name?: string }> }>): Map<string, string[]> {
    const out = new Map<string, string[]>();
    for (const e of enums) {
        if (!e.name) continue;
        for (const m of e.members ?? []) {
            if (!m.name) continue;
            const cName = `${e.name}_${m.name}`;
            out.set(cName, [...(out.get(cName) ?? []), `member ${m.name} of enumeration ${e.name}`]);
        }
    }
    return out;
}

/**
 * Why the C enumeration constant `cName` of member `self` (`member AUTO of enumeration Mode`) cannot
 * be used, or undefined: a file-scope name (as a datatype's), a constant's, a datatype's or
 * enumeration's, a function's, a module port's or parameter's (when `project` lists them), or
 * another member's C name. The check of `contract check` and of a rename of the member.
 */
export function enumConstantConflict(cName: string, self: string, project: ProjectCNames): string | undefined {
    const other = (project.enumConstants?.get(cName) ?? []).find((m) => m !== self);
    return cNameConflict(cName, 'datatype', { ...project, enumConstants: undefined })
        ?? (project.constants?.has(cName) ? 'a named constant has that name, and constants are macros in the generated C (common/constants.h)' : undefined)
        ?? (project.datatypes.has(cName) ? 'a datatype or enumeration has that name, a type name in the generated C' : undefined)
        ?? (project.functions?.has(cName) ? 'a function has that name, a file-scope name in the generated C' : undefined)
        ?? (project.moduleVariables?.has(cName) ? 'a module port or parameter has that name, a global variable of its module.c' : undefined)
        ?? (other ? `${other} becomes the same C enumeration constant` : undefined);
}

/** A name like `name` (`time_`, `time_2`, ...) that `accepts` takes; used by the message and the quick fix. */
export function suggestName(name: string, accepts: (candidate: string) => boolean): string {
    for (let n = 1; n < 100; n++) {
        const candidate = n === 1 ? `${name}_` : `${name}_${n}`;
        if (accepts(candidate)) return candidate;
    }
    return `${name}_`;
}
