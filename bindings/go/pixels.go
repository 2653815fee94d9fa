package mcstat

// #include <stdlib.h>
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
	var none C.struct_mcstat_pixels_out
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
	out := C.struct_mcstat_pixels_out{p_value: col(0), statistic: col(1), df: col(2), mean_x: col(3), mean_y: col(4),
		status: (*C.int32_t)(unsafe.Pointer(stat)), std_error: col(7)}
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
