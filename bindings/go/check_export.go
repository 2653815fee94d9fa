package mcstat

// The C side of the renderer checks' callbacks.  A file with //export may
// hold only declarations in its preamble: the adapters are in check.go.

// #include <stdint.h>
// #include <stddef.h>
import "C"

import (
	"fmt"
	"runtime/cgo"
	"unsafe"
)

func callOf(user unsafe.Pointer) *checkCall {
	return cgo.Handle(*(*C.uintptr_t)(user)).Value().(*checkCall)
}

// doubles views n doubles of libmcstat's memory as a slice (nil for NULL).
func doubles(p *C.double, n int) []float64 {
	if p == nil {
		return nil
	}
	return unsafe.Slice((*float64)(unsafe.Pointer(p)), n)
}

// finish turns a callback's error or panic into a non-zero return, which
// stops the check with MCSTAT_ECALLBACK.
func (c *checkCall) finish(name string, err error, rc *C.int) {
	if err != nil {
		if c.err == nil {
			c.callback, c.err = name, err
		}
		*rc = 1
	}
}

//export gomcstatSample
func gomcstatSample(user unsafe.Pointer, wi, u *C.double, n C.size_t, x, weight, pdf *C.double) (rc C.int) {
	c := callOf(user)
	var err error
	defer func() {
		// a panic must not unwind through C: recover it here (recover works
		// only when called by the deferred function itself)
		if p := recover(); p != nil {
			err = &PanicError{Value: p}
		}
		c.finish("sample", err, &rc)
	}()
	k := int(n)
	err = c.model.Sample(doubles(wi, 3), doubles(u, k*c.nu), doubles(x, k*c.dims), doubles(weight, k), doubles(pdf, k))
	return 0
}

func density(user unsafe.Pointer, name string, wi, x *C.double, n C.size_t, out *C.double) (rc C.int) {
	c := callOf(user)
	var err error
	defer func() {
		// a panic must not unwind through C: recover it here (recover works
		// only when called by the deferred function itself)
		if p := recover(); p != nil {
			err = &PanicError{Value: p}
		}
		c.finish(name, err, &rc)
	}()
	f := c.model.PDF
	if name == "eval" {
		f = c.model.Eval
	}
	k := int(n)
	err = f(doubles(wi, 3), doubles(x, k*c.dims), doubles(out, k))
	return 0
}

//export gomcstatPDF
func gomcstatPDF(user unsafe.Pointer, wi, x *C.double, n C.size_t, out *C.double) C.int {
	return density(user, "pdf", wi, x, n, out)
}

//export gomcstatEval
func gomcstatEval(user unsafe.Pointer, wi, x *C.double, n C.size_t, out *C.double) C.int {
	return density(user, "eval", wi, x, n, out)
}

//export gomcstatLobes
func gomcstatLobes(user unsafe.Pointer, wi, x, mass, value *C.double, count *C.size_t) (rc C.int) {
	c := callOf(user)
	var err error
	defer func() {
		// a panic must not unwind through C: recover it here (recover works
		// only when called by the deferred function itself)
		if p := recover(); p != nil {
			err = &PanicError{Value: p}
		}
		c.finish("lobes", err, &rc)
	}()
	lobes, err := c.model.Lobes(doubles(wi, 3))
	if err != nil {
		return 0
	}
	if len(lobes) > MaxLobes {
		err = fmt.Errorf("gave %d lobes: at most %d", len(lobes), MaxLobes)
		return 0
	}
	// libmcstat's arrays hold MaxLobes lobes
	xs, ms, vs := doubles(x, 3*MaxLobes), doubles(mass, MaxLobes), doubles(value, MaxLobes)
	for k, l := range lobes {
		copy(xs[3*k:3*k+3], l.Dir[:])
		ms[k], vs[k] = l.Mass, l.Value
	}
	*count = C.size_t(len(lobes))
	return 0
}
