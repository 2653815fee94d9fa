package mcstat

// #include <stdlib.h>
// #include <string.h>
// #include <mcstat.h>
import "C"

import (
	"fmt"
	"math"
	"unsafe"
)

// ---- per-pixel Welch on seeds-major images --------------------------------------

// PixelResults are TTest2Pixels' outputs, one entry per pixel.  A pixel
// that could not be tested (too few values, NaN or Inf, constant in both
// samples) has its status in Status and NaN elsewhere.  ConfLo and ConfHi
// are nil with NoIntervals.
type PixelResults struct {
	PValue, Statistic, DF, MeanX, MeanY []float64
	StdError                            []float64 // Welch's standard error of MeanX - MeanY
	ConfLo, ConfHi                      []float64
	Status                              []int32
}

// pixelSizes checks that nx seeds of pixels*channels values fit in n values
// and that the weights match the channels.
func pixelSizes(name string, n, seeds, pixels, channels int, weights []float64) error {
	if seeds < 0 || pixels < 0 || channels < 1 {
		return invalid(name + ": negative seeds or pixels, or channels < 1")
	}
	if weights == nil && channels != 1 {
		return invalid(fmt.Sprintf("%s: %d channels need one weight each", name, channels))
	}
	if weights != nil && len(weights) != channels {
		return invalid(fmt.Sprintf("%s: %d weights for %d channels", name, len(weights), channels))
	}
	if pixels > 0 && channels > math.MaxInt/pixels {
		return invalid(name + ": pixels * channels overflows")
	}
	plane := pixels * channels
	if plane > 0 && seeds > math.MaxInt/plane {
		return invalid(name + ": seeds * pixels * channels overflows")
	}
	if seeds*plane > n {
		return invalid(fmt.Sprintf("%s: %d seeds of %d pixels x %d channels need %d values, got %d", name, seeds,
			pixels, channels, seeds*plane, n))
	}
	return nil
}

// runPixels calls f with outputs in C memory (a Go struct handed to C may
// not hold Go pointers) and copies them out.
func runPixels(pixels int, flags RowFlags, f func(out *C.struct_mcstat_pixels_out, begin, end C.size_t) C.int) (*PixelResults, error) {
	none := pixelsOutInit()
	if st := f(&none, 0, 0); st != C.MCSTAT_OK { // the arguments, on an empty range
		return nil, newError(st)
	}
	n := pixels
	if n == 0 {
		n = 1
	}
	buf := (*float64)(C.malloc(C.size_t(n) * 8 * 8))
	stat := (*int32)(C.malloc(C.size_t(n) * 4))
	if buf == nil || stat == nil {
		C.free(unsafe.Pointer(buf))
		C.free(unsafe.Pointer(stat))
		return nil, newError(C.MCSTAT_ENOMEM)
	}
	defer C.free(unsafe.Pointer(buf))
	defer C.free(unsafe.Pointer(stat))
	d := unsafe.Slice(buf, 8*n)
	col := func(k int) *C.double { return (*C.double)(unsafe.Pointer(&d[k*n])) }
	intervals := flags&NoIntervals == 0
	out := pixelsOutInit()
	out.p_value, out.statistic, out.df, out.estimate, out.estimate2 = col(0), col(1), col(2), col(3), col(4)
	out.status, out.std_error = (*C.int32_t)(unsafe.Pointer(stat)), col(7)
	if intervals {
		out.conf_lo = col(5)
		out.conf_hi = col(6)
	}
	st := f(&out, 0, C.size_t(pixels))
	get := func(k int) []float64 { return append([]float64(nil), d[k*n:k*n+pixels]...) }
	r := &PixelResults{PValue: get(0), Statistic: get(1), DF: get(2), MeanX: get(3), MeanY: get(4), StdError: get(7),
		Status: append([]int32(nil), unsafe.Slice(stat, n)[:pixels]...)}
	if intervals {
		r.ConfLo, r.ConfHi = get(5), get(6)
	}
	return r, check(st)
}

// pixelsOutInit is MCSTAT_PIXELS_OUT_INIT: the size set, every array nil.
func pixelsOutInit() C.struct_mcstat_pixels_out {
	var o C.struct_mcstat_pixels_out
	C.mcstat_pixels_out_init_size(&o, C.sizeof_struct_mcstat_pixels_out)
	return o
}

func wptr(w []float64) *C.double {
	if len(w) == 0 {
		return nil
	}
	return (*C.double)(unsafe.Pointer(&w[0]))
}

// TTest2Pixels is Welch's test per pixel of x against y, images written
// seeds-major as renderers write them: seed s of pixel i, channel c is
// x[s*pixels*channels + i*channels + c].  With weights (one per channel)
// the tested value is sum_c weights[c] x[...] (luminance from RGB);
// weights nil with channels 1 tests the values themselves.  Each pixel
// agrees with TTest2 on its two samples (libmcstat's
// mcstat_t_test_2_pixels).  The error is the first failing pixel's, as
// TTest2Matrix reports its rows; bad arguments give nil results.
func TTest2Pixels(x []float64, nx int, y []float64, ny int, pixels, channels int, weights []float64, mu0 float64,
	alt Alternative, alpha float64, flags RowFlags) (*PixelResults, error) {
	if err := pixelSizes("x", len(x), nx, pixels, channels, weights); err != nil {
		return nil, err
	}
	if err := pixelSizes("y", len(y), ny, pixels, channels, weights); err != nil {
		return nil, err
	}
	stride := sz(pixels * channels)
	return runPixels(pixels, flags, func(o *C.struct_mcstat_pixels_out, b, e C.size_t) C.int {
		return C.mcstat_t_test_2_pixels(ptr(x), sz(nx), stride, ptr(y), sz(ny), stride, sz(channels), wptr(weights),
			b, e, C.double(mu0), C.int(alt), C.double(alpha), C.uint(flags), o)
	})
}

// TTest2PixelsF32 is TTest2Pixels on float32 images (read as they are;
// the sums are formed in float64).
func TTest2PixelsF32(x []float32, nx int, y []float32, ny int, pixels, channels int, weights []float64, mu0 float64,
	alt Alternative, alpha float64, flags RowFlags) (*PixelResults, error) {
	if err := pixelSizes("x", len(x), nx, pixels, channels, weights); err != nil {
		return nil, err
	}
	if err := pixelSizes("y", len(y), ny, pixels, channels, weights); err != nil {
		return nil, err
	}
	fp := func(v []float32) *C.float {
		if len(v) == 0 {
			return nil
		}
		return (*C.float)(unsafe.Pointer(&v[0]))
	}
	stride := sz(pixels * channels)
	return runPixels(pixels, flags, func(o *C.struct_mcstat_pixels_out, b, e C.size_t) C.int {
		return C.mcstat_t_test_2_pixels_f32(fp(x), sz(nx), stride, fp(y), sz(ny), stride, sz(channels), wptr(weights),
			b, e, C.double(mu0), C.int(alt), C.double(alpha), C.uint(flags), o)
	})
}

// ---- any test per pixel, any layout: mcstat_pixels_test -------------------------

// PixelTest names the tests of PixelsTest.
type PixelTest int

const (
	PixelT1       PixelTest = C.MCSTAT_TEST_T_1        // one-sample t of x's mean
	PixelT2       PixelTest = C.MCSTAT_TEST_T_2        // Welch's t of mean(x) - mean(y)
	PixelT2Pooled PixelTest = C.MCSTAT_TEST_T_2_POOLED // Student's pooled t
	PixelTPaired  PixelTest = C.MCSTAT_TEST_T_PAIRED   // paired t of mean(x - y), equal N
	PixelVar1     PixelTest = C.MCSTAT_TEST_VAR_1      // chi-squared test of x's variance
	PixelVar2     PixelTest = C.MCSTAT_TEST_VAR_2      // F test of var(x) / var(y)
)

func (t PixelTest) twoSample() bool { return t != PixelT1 && t != PixelVar1 }

// Pixels says where the values of each pixel are: value s of pixel i
// starts at element s*ValueStride + i*PixelStride of F64 (or F32: set
// one of the two) and is the weighted sum of Channels consecutive
// elements there (Weights, one per channel; nil with Channels 1: the
// element itself; Channels 0 means 1).  A seeds-major stack of P pixels:
// ValueStride P, PixelStride 1; rows of N values per pixel: ValueStride 1,
// PixelStride N.
type Pixels struct {
	F64                      []float64
	F32                      []float32
	N                        int
	ValueStride, PixelStride int
	Channels                 int
	Weights                  []float64
}

// PixelTestResults are PixelsTest's outputs, one entry per pixel (the
// arrays of mcstat.h's mcstat_pixels_out).  A pixel that failed has its
// status in Status, NaN elsewhere, Decision 0, NX and NY 0.  With
// NoIntervals the intervals and critical values are NaN.
type PixelTestResults struct {
	PValue, Statistic []float64
	DF, DF2           []float64 // DF2: F's denominator df (NaN for the others)
	// Estimate is the single call's estimate[0] (x's mean; the variance;
	// the ratio of variances), Estimate2 y's mean (two-sample t; NaN else).
	Estimate, Estimate2    []float64
	StdError               []float64
	ConfLo, ConfHi         []float64
	CriticalLo, CriticalHi []float64
	Status                 []int32
	Decision               []int8 // -1, 0, +1
	NX, NY                 []uint64
}

// PixelStructSizes are sizeof(mcstat_pixels_in), sizeof(mcstat_pixels_options)
// and sizeof(mcstat_pixels_out) as libmcstat was built.
func PixelStructSizes() (in, options, out int) {
	return int(C.mcstat_sizeof_pixels_in()), int(C.mcstat_sizeof_pixels_options()), int(C.mcstat_sizeof_pixels_out())
}

// elements checks that every element pixels pixels address lies in the
// slice, and returns the slice's length.
func (p Pixels) elements(name string, pixels int) (int, error) {
	if (p.F64 == nil) == (p.F32 == nil) && !(p.F64 == nil && p.F32 == nil && (pixels == 0 || p.N == 0)) {
		return 0, invalid(name + ": set exactly one of F64 and F32")
	}
	ch := p.Channels
	if ch == 0 {
		ch = 1
	}
	if ch < 0 || p.N < 0 || p.ValueStride < 0 || p.PixelStride < 0 || pixels < 0 {
		return 0, invalid(name + ": negative sizes or strides")
	}
	if p.Weights == nil && ch != 1 {
		return 0, invalid(fmt.Sprintf("%s: %d channels need one weight each", name, ch))
	}
	if p.Weights != nil && len(p.Weights) != ch {
		return 0, invalid(fmt.Sprintf("%s: %d weights for %d channels", name, len(p.Weights), ch))
	}
	n := len(p.F64)
	if p.F32 != nil {
		n = len(p.F32)
	}
	if pixels == 0 || p.N == 0 {
		return n, nil
	}
	mul := func(a, b int) (int, bool) {
		if a != 0 && b > math.MaxInt/a {
			return 0, false
		}
		return a * b, true
	}
	a, ok1 := mul(p.N-1, p.ValueStride)
	b, ok2 := mul(pixels-1, p.PixelStride)
	if !ok1 || !ok2 || a > math.MaxInt-b-(ch-1) || a+b+ch-1 >= n {
		return 0, invalid(fmt.Sprintf("%s: %d values of %d pixels (strides %d and %d, %d channels) do not fit in %d "+
			"elements", name, p.N, pixels, p.ValueStride, p.PixelStride, ch, n))
	}
	return n, nil
}

// cIn is p as an mcstat_pixels_in over a copy of its values in C memory
// (a Go struct handed to C may not hold Go pointers); free releases it.
func (p Pixels) cIn(n int) (in C.struct_mcstat_pixels_in, free func(), err error) {
	C.mcstat_pixels_in_init_size(&in, C.sizeof_struct_mcstat_pixels_in)
	size := 8
	var src unsafe.Pointer
	if p.F32 != nil {
		size = 4
		in._type = C.MCSTAT_VALUE_FLOAT32
		if n > 0 {
			src = unsafe.Pointer(&p.F32[0])
		}
	} else if n > 0 {
		src = unsafe.Pointer(&p.F64[0])
	}
	ch := p.Channels
	if ch == 0 {
		ch = 1
	}
	data := C.malloc(C.size_t(n*size + 8))
	var w unsafe.Pointer
	if p.Weights != nil {
		w = C.malloc(C.size_t(8 * len(p.Weights)))
	}
	if data == nil || (p.Weights != nil && w == nil) {
		C.free(data)
		C.free(w)
		return in, nil, newError(C.MCSTAT_ENOMEM)
	}
	if n > 0 {
		C.memcpy(data, src, C.size_t(n*size))
	}
	if w != nil {
		C.memcpy(w, unsafe.Pointer(&p.Weights[0]), C.size_t(8*len(p.Weights)))
	}
	in.data = data
	in.n, in.value_stride, in.pixel_stride, in.channels = sz(p.N), sz(p.ValueStride), sz(p.PixelStride), sz(ch)
	in.weights = (*C.double)(w)
	return in, func() { C.free(data); C.free(w) }, nil
}

// PixelsTest runs test once per pixel 0..pixels-1 of x (and y for the
// two-sample tests; nil for PixelT1 and PixelVar1): libmcstat's
// mcstat_pixels_test.  Each pixel's results are the single call's on its
// values (bit for bit but for Welch's and the variance tests, within the
// bounds of mcstat.h).  threads (1..64) threads take the pixels by chunks
// in turn; results do not depend on it.  The values are
// copied into C memory for the call.  The error is the first failing
// pixel's (its status is in Status); bad arguments give nil results.
func PixelsTest(test PixelTest, x Pixels, y *Pixels, pixels int, nullValue float64, alt Alternative, alpha float64,
	flags RowFlags, threads int) (*PixelTestResults, error) {
	if test.twoSample() != (y != nil) {
		if y == nil {
			return nil, invalid("PixelsTest: this test needs y")
		}
		return nil, invalid("PixelsTest: a one-sample test takes no y")
	}
	if threads < 1 || threads > 64 {
		return nil, invalid(fmt.Sprintf("PixelsTest: threads must be in 1..64, got %d", threads))
	}
	nx, err := x.elements("x", pixels)
	if err != nil {
		return nil, err
	}
	cx, freeX, err := x.cIn(nx)
	if err != nil {
		return nil, err
	}
	defer freeX()
	var cy C.struct_mcstat_pixels_in
	var py *C.struct_mcstat_pixels_in
	if y != nil {
		ny, err := y.elements("y", pixels)
		if err != nil {
			return nil, err
		}
		var freeY func()
		if cy, freeY, err = y.cIn(ny); err != nil {
			return nil, err
		}
		defer freeY()
		py = &cy
	}
	var opt C.struct_mcstat_pixels_options
	C.mcstat_pixels_options_init_size(&opt, C.sizeof_struct_mcstat_pixels_options)
	opt.flags = C.uint32_t(flags)
	opt.threads = C.int32_t(threads)
	call := func(out *C.struct_mcstat_pixels_out, end int) C.int {
		return C.mcstat_pixels_test(C.int(test), &cx, py, 0, sz(end), C.double(nullValue), C.int(alt),
			C.double(alpha), &opt, out)
	}
	none := pixelsOutInit()
	if st := call(&none, 0); st != C.MCSTAT_OK { // the arguments, on an empty range
		return nil, newError(st)
	}
	n := pixels
	if n == 0 {
		n = 1
	}
	const cols = 11 // the float64 outputs
	buf := (*float64)(C.malloc(C.size_t(n * 8 * cols)))
	stat := (*int32)(C.malloc(C.size_t(n * 4)))
	dec := (*int8)(C.malloc(C.size_t(n)))
	sizes := (*uint64)(C.malloc(C.size_t(n * 16)))
	defer C.free(unsafe.Pointer(buf))
	defer C.free(unsafe.Pointer(stat))
	defer C.free(unsafe.Pointer(dec))
	defer C.free(unsafe.Pointer(sizes))
	if buf == nil || stat == nil || dec == nil || sizes == nil {
		return nil, newError(C.MCSTAT_ENOMEM)
	}
	d := unsafe.Slice(buf, cols*n)
	col := func(k int) *C.double { return (*C.double)(unsafe.Pointer(&d[k*n])) }
	ns := unsafe.Slice(sizes, 2*n)
	out := pixelsOutInit()
	out.p_value, out.statistic, out.df, out.df2, out.estimate, out.estimate2 = col(0), col(1), col(2), col(3), col(4), col(5)
	out.std_error, out.conf_lo, out.conf_hi, out.critical_lo, out.critical_hi = col(6), col(7), col(8), col(9), col(10)
	out.status, out.decision = (*C.int32_t)(unsafe.Pointer(stat)), (*C.int8_t)(unsafe.Pointer(dec))
	out.n_x, out.n_y = (*C.uint64_t)(unsafe.Pointer(&ns[0])), (*C.uint64_t)(unsafe.Pointer(&ns[n]))
	st := call(&out, pixels)
	get := func(k int) []float64 { return append([]float64(nil), d[k*n:k*n+pixels]...) }
	r := &PixelTestResults{PValue: get(0), Statistic: get(1), DF: get(2), DF2: get(3), Estimate: get(4),
		Estimate2: get(5), StdError: get(6), ConfLo: get(7), ConfHi: get(8), CriticalLo: get(9), CriticalHi: get(10),
		Status:   append([]int32(nil), unsafe.Slice(stat, n)[:pixels]...),
		Decision: append([]int8(nil), unsafe.Slice(dec, n)[:pixels]...),
		NX:       append([]uint64(nil), ns[:pixels]...), NY: append([]uint64(nil), ns[n:n+pixels]...)}
	return r, check(st)
}
