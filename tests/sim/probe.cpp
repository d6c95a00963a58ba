// calibration probe (not committed)
#include <chrono>
#include <cstdio>
#include <map>
#include <cmath>
#include "app/platform/gl_context.h"
#include "study/design/design.h"
#include "study/session/mapping.h"
#include "study/sim/sim.h"
using namespace dtlab;
int main(int argc,char**argv){
  int N=argc>1?atoi(argv[1]):4; int W=160,H=120;
  std::string only = argc>2?argv[2]:"";
  int verbose = argc>3?atoi(argv[3]):1;
  auto ctx=platform::create_headless(W,H);
  auto p=protocol::load_protocol(std::string(DTLAB_SOURCE_DIR)+"/protocols/elmqvist2008.toml").value();
  sim::SimOptions so; so.width=W; so.height=H;
  sim::SimulatedParticipant agent(so);
  struct Acc{double t=0,t2=0,err=0,views=0,wall=0,frames=0; int n=0;};
  std::map<std::string,Acc> acc;
  int K0 = getenv("K0")?atoi(getenv("K0")):0;
  for(int k=K0;k<N;k++){
    design::Plan plan=design::make_plan(p,k);
    for(auto t: plan.trials){
      if(t.trial!=1 || t.method!="standard") continue;
      if(!only.empty() && only.find(t.task)==std::string::npos) continue;
      for (int mi=0; mi<2; ++mi) {
        auto setup=session::trial_setup(p,t).value();
        setup.rendering=&p.renderings[mi]; t.method=p.renderings[mi].method;
        auto sc=session::trial_scene(setup,t).value();
        session::TrialSpec spec; spec.protocol=&p; spec.enrollment_index=k; spec.planned=t; spec.planned_trials=24; spec.setup=&setup; spec.scene=&sc;
        spec.frame=session::frame_settings(p,*setup.rendering,W,H).value(); spec.time_limit_s=3600;
        auto w0=std::chrono::steady_clock::now();
        auto o=agent.run_trial(spec).value();
        double wall=std::chrono::duration<double>(std::chrono::steady_clock::now()-w0).count();
        auto tr=agent.last_trace();
        auto sc2=store::score(o.answer,session::answer_key(sc.answer));
        double e = sc2.rel_error? *sc2.rel_error : sc2.correct ? (*sc2.correct?1:0) : sc2.distance? *sc2.distance : -1;
        auto&a=acc[t.task+" "+t.method]; a.t+=o.completion_s; a.t2+=o.completion_s*o.completion_s; a.err+=e; a.views+=tr.views; a.wall+=wall; a.frames+=o.frame_ms.size(); a.n++;
        std::string nv; for(size_t i=0;i<tr.noticed.size()&&i<14;i++){ nv+=std::to_string(tr.visible[i])+"/"+std::to_string(tr.noticed[i])+" ";}
        if(verbose) printf("k%d %s %-8s t=%6.1f err=%.3f views=%d frames=%zu wall=%.2f  vis/noticed: %s\n",k,t.task.c_str(),t.method.c_str(),o.completion_s,e,tr.views,o.frame_ms.size(),wall,nv.c_str());
      }
    }
  }
  for(auto&[k,a]:acc){ double m=a.t/a.n; double sd=a.n>1?std::sqrt(std::max(0.0,(a.t2-a.n*m*m)/(a.n-1))):0; printf("%-14s n=%d time %.1f (%.1f) err %.3f views %.1f frames %.1f wall/trial %.2f\n",k.c_str(),a.n,m,sd,a.err/a.n,a.views/a.n,a.frames/a.n,a.wall/a.n);}
}
