/* Arithmetic throughput of one core: 12 independent chains of AVX-512 multiply-adds
 * (16 floats each), then one dependent chain (latency). Built with
 * gcc -O2 -mavx512f -mfma; run alone, two at once and sixteen at once
 * (2026-11-27_fma_throughput.txt). */
#include <immintrin.h>
#include <stdio.h>
#include <time.h>
#include <stdlib.h>
static double now(void){struct timespec t;clock_gettime(CLOCK_MONOTONIC,&t);return t.tv_sec+1e-9*t.tv_nsec;}
int main(int argc,char**argv){
  long n = argc>1? atol(argv[1]) : 200000000L;
  __m512 a[12]; __m512 m=_mm512_set1_ps(0.999999f), c=_mm512_set1_ps(1e-7f);
  for(int i=0;i<12;i++) a[i]=_mm512_set1_ps((float)i);
  double t0=now();
  for(long i=0;i<n;i++){
    #pragma GCC unroll 12
    for(int k=0;k<12;k++) a[k]=_mm512_fmadd_ps(a[k],m,c);
  }
  double t=now()-t0;
  __m512 s=a[0]; for(int i=1;i<12;i++) s=_mm512_add_ps(s,a[i]);
  float out[16]; _mm512_storeu_ps(out,s);
  printf("zmm FMAs/ns %.3f  (%.1f GFLOP/s)  chk %g\n", 12.0*n/t*1e-9, 12.0*n*32/t*1e-9, out[0]);
  /* dependent chain: latency */
  __m512 x=_mm512_set1_ps(1.0f); t0=now();
  for(long i=0;i<n/4;i++){ x=_mm512_fmadd_ps(x,m,c);}
  t=now()-t0; _mm512_storeu_ps(out,x);
  printf("dependent zmm FMA ns each %.3f chk %g\n", t/(n/4)*1e9, out[0]);
  return 0;
}
