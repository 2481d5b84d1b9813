//! The code of one stopping point (`Body`): the varying operations in the interpreter's order,
//! each value kept in a register, then the outputs stored; and the Rust functions it calls.

use super::super::super::{Func, Op};
use super::{Plan, Step};
use cranelift_codegen::ir::{
    types, AbiParam, InstBuilder, MemFlags, SigRef, StackSlotData, StackSlotKind, Value,
};
use cranelift_frontend::FunctionBuilder;
use cranelift_jit::JITModule;
use cranelift_module::Module;

/// The signatures of the Rust functions the code calls.
pub(super) struct Calls {
    /// `(f64, f64) -> f64`: a function of one or two arguments, a power.
    binary: SigRef,
    /// `(f64, *mut f64)`: sin and cos into two adjacent values.
    sin_cos: SigRef,
}

impl Calls {
    pub(super) fn new(module: &JITModule, b: &mut FunctionBuilder, ptr: types::Type) -> Calls {
        let mut binary = module.make_signature();
        binary.params.extend([AbiParam::new(types::F64); 2]);
        binary.returns.push(AbiParam::new(types::F64));
        let mut sin_cos = module.make_signature();
        sin_cos
            .params
            .extend([AbiParam::new(types::F64), AbiParam::new(ptr)]);
        Calls {
            binary: b.import_signature(binary),
            sin_cos: b.import_signature(sin_cos),
        }
    }
}

/// One stopping point's function being built.
pub(super) struct Body<'a, 'b> {
    plan: &'a Plan<'a>,
    b: FunctionBuilder<'b>,
    ptr: types::Type,
    calls: Calls,
    /// Each slot's value where this function has it.
    values: Vec<Option<Value>>,
    /// The buffer's address.
    buf: Value,
    /// The address of the output groups' addresses.
    outs: Value,
}

/// Every load and store: of the buffer, the varying variables and the output slices, aligned
/// and in bounds (their lengths checked by `Split::eval` before a call), so never trapping.
const FLAGS: MemFlags = MemFlags::trusted();

impl<'a, 'b> Body<'a, 'b> {
    pub(super) fn new(
        plan: &'a Plan<'a>,
        mut b: FunctionBuilder<'b>,
        ptr: types::Type,
        calls: Calls,
    ) -> Self {
        let block = b.create_block();
        b.append_block_params_for_function_params(block);
        b.switch_to_block(block);
        let [buf, head, last, outs] =
            <[Value; 4]>::try_from(b.block_params(block)).expect("the four parameters of `Entry`");
        let mut values = vec![None; plan.len + 1];
        let (&last_slot, heads) = plan.slots.split_last().expect("a varying variable");
        for (i, &s) in heads.iter().enumerate() {
            values[s] = Some(b.ins().load(types::F64, FLAGS, head, 8 * i as i32));
        }
        values[last_slot] = Some(last);
        Body {
            plan,
            b,
            ptr,
            calls,
            values,
            buf,
            outs,
        }
    }

    /// Slot `s`'s value: computed here, or the buffer's.
    fn get(&mut self, s: u32) -> Value {
        let s = s as usize;
        if let Some(v) = self.values[s] {
            return v;
        }
        let v = self.b.ins().load(types::F64, FLAGS, self.buf, 8 * s as i32);
        self.values[s] = Some(v);
        v
    }

    /// A call of the Rust function `f` on `a` and `b`.
    fn call(&mut self, f: extern "C" fn(f64, f64) -> f64, a: Value, b: Value) -> Value {
        let callee = self.b.ins().iconst(self.ptr, f as usize as i64);
        let call = self
            .b
            .ins()
            .call_indirect(self.calls.binary, callee, &[a, b]);
        self.b.inst_results(call)[0]
    }

    /// The operations of stopping point `end`, then its outputs, and the return.
    pub(super) fn emit(mut self, end: usize) {
        for step in &self.plan.steps[..self.plan.ends[end]] {
            let (out, v) = match *step {
                Step::Neg(a, out) => {
                    let a = self.get(a);
                    (out, self.b.ins().fneg(a))
                }
                Step::Add(a, c, out) => self.binary(Op::Add, a, c, out),
                Step::Sub(a, c, out) => self.binary(Op::Sub, a, c, out),
                Step::Mul(a, c, out) => self.binary(Op::Mul, a, c, out),
                Step::Div(a, c, out) => self.binary(Op::Div, a, c, out),
                Step::Bin(op, a, c, out) => self.binary(op, a, c, out),
                Step::Call(f, a, c, out) => {
                    let (a, c) = (self.get(a), self.get(c));
                    let v = match f {
                        Func::Sqrt => self.b.ins().sqrt(a),
                        Func::Abs => self.b.ins().fabs(a),
                        _ => self.call(callee(f), a, c),
                    };
                    (out, v)
                }
                Step::SinCos { arg, sin, cos } => {
                    let a = self.get(arg);
                    let slot = (self.b).create_sized_stack_slot(StackSlotData::new(
                        StackSlotKind::ExplicitSlot,
                        16,
                        3,
                    ));
                    let at = self.b.ins().stack_addr(self.ptr, slot, 0);
                    let callee = self
                        .b
                        .ins()
                        .iconst(self.ptr, sin_cos as *const () as usize as i64);
                    self.b
                        .ins()
                        .call_indirect(self.calls.sin_cos, callee, &[a, at]);
                    self.values[sin as usize] = Some(self.b.ins().stack_load(types::F64, slot, 0));
                    self.values[cos as usize] = Some(self.b.ins().stack_load(types::F64, slot, 8));
                    continue;
                }
            };
            self.values[out as usize] = Some(v);
        }
        let mut from = 0;
        for (g, &to) in self.plan.groups[..=end].iter().enumerate() {
            let dest = self.b.ins().load(self.ptr, FLAGS, self.outs, 8 * g as i32);
            for k in from..to {
                let v = self.get(self.plan.outputs[k]);
                self.b.ins().store(FLAGS, v, dest, 8 * (k - from) as i32);
            }
            from = to;
        }
        self.b.ins().return_(&[]);
        self.b.seal_all_blocks();
        self.b.finalize();
    }

    /// `op` on slots `a` and `c`, for slot `out`.
    fn binary(&mut self, op: Op, a: u32, c: u32, out: u32) -> (u32, Value) {
        let (a, c) = (self.get(a), self.get(c));
        let v = match op {
            Op::Add => self.b.ins().fadd(a, c),
            Op::Sub => self.b.ins().fsub(a, c),
            Op::Mul => self.b.ins().fmul(a, c),
            Op::Div => self.b.ins().fdiv(a, c),
            Op::Pow => self.call(power, a, c),
        };
        (out, v)
    }
}

extern "C" fn power(a: f64, b: f64) -> f64 {
    Op::Pow.apply(a, b)
}

extern "C" fn sin_cos(a: f64, out: *mut f64) {
    let (s, c) = a.sin_cos();
    // SAFETY: `out` is the caller's 16-byte stack slot.
    unsafe {
        out.write(s);
        out.add(1).write(c);
    }
}

/// The Rust function the code calls for `f` (the interpreter's `Func::apply`).
fn callee(f: Func) -> extern "C" fn(f64, f64) -> f64 {
    macro_rules! each {
        ($($name:ident),*) => {
            match f {
                $(Func::$name => {
                    extern "C" fn apply(a: f64, b: f64) -> f64 {
                        Func::$name.apply(a, b)
                    }
                    apply
                })*
            }
        };
    }
    each!(Sqrt, Exp, Ln, Sin, Cos, Tan, Tanh, Abs, Min, Max, Sign, Step)
}
