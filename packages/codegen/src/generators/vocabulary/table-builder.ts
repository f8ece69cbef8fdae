import type { FunctionPrototype, TypeRef, Value } from '../../model/architecture.js';
import type { ArchitectureIndex } from '../../model/lookup.js';
import { cInitializer, cType } from '../c/c-syntax.js';
import { cPointerType } from '../shared-function-header.js';

/**
 * Collects the static C definitions of a vocabulary.c (seam 2, runtime/include/contract/vocabulary.h)
 * in dependency order. Only what is referenced is emitted (no unused static: zero warnings).
 */
export class TableBuilder {
    private readonly definitions: string[] = [];
    private readonly usedTypes = new Set<string>();
    private readonly usedHeaders = new Set<string>();
    private readonly constants = new Map<string, string>();
    private readonly functions = new Map<string, string>();
    private readonly names = new Set<string>();

    constructor(readonly index: ArchitectureIndex) {
        // the common/ headers a vocabulary.c includes declare these: table names keep clear of them
        for (const n of userFileScopeNames(index)) this.names.add(n);
    }

    /** Appends a definition (a complete C declaration). */
    define(text: string): void {
        this.definitions.push(text);
    }

    /** A fresh identifier based on `base` (deterministic: numbered in order of creation). */
    unique(base: string): string {
        let name = base;
        for (let n = 2; this.names.has(name); n++) name = `${base}_${n}`;
        this.names.add(name);
        return name;
    }

    /** `&contract_type_X` for a type, recording that its descriptor is needed. */
    typeRef(t: TypeRef): string {
        if ('primitive' in t) return `&contract_type_${t.primitive === 'int' ? 'long' : t.primitive === 'float' ? 'double' : 'string'}`;
        for (const d of this.index.datatypeClosure(t)) this.usedHeaders.add(d);
        this.usedTypes.add(t.datatype);
        return `&contract_type_${t.datatype}`;
    }

    /** A static constant of type `t` holding `value` (or the type's default), shared when identical. Returns `&name`. */
    constant(t: TypeRef, value: Value | undefined): string {
        const init = cInitializer(this.index, t, value);
        const key = `${JSON.stringify(t)}=${init}`;
        const known = this.constants.get(key);
        if (known) return known;
        if ('datatype' in t) this.typeRef(t);
        const name = this.unique(`k_${this.constants.size}`);
        const decl = 'primitive' in t && t.primitive === 'string' ? `static const char ${name}[256] = ${init};` : `static const ${cType(t)} ${name} = ${init};`;
        this.define(decl);
        this.constants.set(key, `&${name}`);
        return `&${name}`;
    }

    /** `&fn_<f>`: the ContractUserFunction adapter of a user function. */
    userFunction(f: FunctionPrototype): string {
        let adapter = this.functions.get(f.name);
        if (!adapter) {
            this.usedHeaders.add(`Function${f.name}`);
            const types = f.args.map((a) => this.typeRef(a.type));
            const argTypes = types.length ? this.unique(`fnargs_${f.name}`) : 'NULL';
            if (types.length) this.define(`static const ContractType *const ${argTypes}[] = {${types.join(', ')}};`);
            const call = `${f.name}(${f.args.map((a, i) => `(${cPointerType(a.type)})a[${i}]`).join(', ')})`;
            const body = f.returns === 'bool' ? `return ${call};` : `${call}; return 0;`;
            const caller = this.unique(`call_${f.name}`);
            this.define(`static int ${caller}(void **a) { ${f.args.length ? '' : '(void)a; '}${body} }`);
            adapter = this.unique(`fn_${f.name}`);
            this.define(`static const ContractUserFunction ${adapter} = {"${f.name}", ${f.returns === 'bool' ? 1 : 0}, ${f.args.length}, ${argTypes}, ${caller}};`);
            this.functions.set(f.name, adapter);
        }
        return `&${adapter}`;
    }

    /** Defines `static const <ctype> <name>[] = {...};` and returns the name, or NULL for no items. */
    array(base: string, ctype: string, items: string[]): string {
        if (items.length === 0) return 'NULL';
        const name = this.unique(base);
        this.define(`static const ${ctype} ${name}[] = {\n    ${items.join(',\n    ')}};`);
        return name;
    }

    /** Includes and type descriptors, then the collected definitions. */
    render(header: string[]): string {
        const types = [...this.usedTypes];
        // descriptors only for used types; dependency order from the headers set keeps includes valid
        const headers = [...this.usedHeaders].sort().map((h) => `#include "Shared${h}.h"`);
        const descriptors = this.index.architecture.datatypes
            .filter((d) => types.includes(d.name))
            .map((d) => `static const ${d.name} contract_default_${d.name} = ${cInitializer(this.index, { datatype: d.name })};\nCONTRACT_DEFINE_TYPE(${d.name}, &contract_default_${d.name})`);
        return [...header, ...headers, '', ...descriptors, '', ...this.definitions, ''].join('\n');
    }
}

/** Functions of common/Shared<T>.h (shared-type-header.ts) and of CONTRACT_DEFINE_TYPE (contract/vocabulary.h). */
const TYPE_FUNCTIONS = ['serialize', 'deserialize', 'diff', 'eq', 'inf', 'sup', 'infeq', 'supeq', 'set', 'get', 'print'];

/**
 * File-scope names of the user's datatypes and functions and of what their headers declare:
 * `check` keeps them from the C library's (docs/language-reference.md, "Reserved names"), the
 * tables of vocabulary.c keep clear of them here (a supervision function `get` next to a datatype
 * `params` would otherwise define a table `get_params`, the datatype's parser).
 */
function userFileScopeNames(index: ArchitectureIndex): string[] {
    const { datatypes, functions } = index.architecture;
    return [
        ...datatypes.flatMap((d) => [d.name, ...TYPE_FUNCTIONS.map((f) => `${f}_${d.name}`)]),
        ...functions.map((f) => f.name)
    ];
}
